//! Every shape: rays aimed at analytically known points hit at the analytic distance with
//! the analytic outward normal and the dicer's (u, v); rays through cut-away regions miss.

mod common;

use std::f32::consts::PI;

use common::{ball, close, close_v, object, placed, scene};
use glam::{Mat3, Mat4, Vec3};
use reyes_scene::object_to_world;
use reyes_scene::{Faces, Shape, Transform};
use reyes_trace::{Hit, Tracer};

const REL: f32 = 1e-4;

fn tracer(shape: Shape, transform: Vec<Transform>) -> Tracer {
    Tracer::new(&scene(vec![object(shape, transform)]))
}

fn shoot(t: &Tracer, origin: Vec3, dir: Vec3) -> Option<Hit> {
    common::shoot(t, origin, dir, 0.0)
}

/// Fires at the object-space point `p` (outward normal `n`) of an object with matrix `m`
/// from outside along the world normal and from an oblique direction, checking `t`, the
/// point, the normal and `(u, v)`.
fn check_point(t: &Tracer, m: Mat4, p: Vec3, n: Vec3, uv: (f32, f32), what: &str) {
    let pw = m.transform_point3(p);
    let nw = (Mat3::from_mat4(m).inverse().transpose() * n).normalize();
    let tangent = nw.any_orthonormal_vector();
    // Along the normal: t is the offset.
    for (offset, dir, expect_t) in
        [(nw * 0.9, -nw, 0.9), (nw * 0.05 + tangent * 0.02, -(nw * 0.05 + tangent * 0.02), 1.0)]
    {
        let origin = pw + offset;
        let Some(hit) = shoot(t, origin, dir) else { panic!("{what}: missed {pw} from {origin}") };
        assert!(close(hit.t, expect_t, REL), "{what}: t {} vs {expect_t} at {pw}", hit.t);
        assert!(close_v(hit.p_world, pw, 1e-4), "{what}: p {} vs {pw}", hit.p_world);
        assert!(close_v(hit.n_world, nw, 1e-4), "{what}: n {} vs {nw} at {pw}", hit.n_world);
        assert!(
            close(hit.u, uv.0, 1e-4) && close(hit.v, uv.1, 1e-4),
            "{what}: uv {:?} vs {uv:?}",
            (hit.u, hit.v)
        );
        assert_eq!(hit.object, 0);
    }
}

fn placements() -> Vec<Vec<Transform>> {
    vec![vec![], placed([1.0, 1.5, 0.75], 35.0, [1.0, 2.0, 0.5], [0.5, -1.0, 2.0])]
}

#[test]
fn sphere_points_hit_with_outward_normals() {
    let (r, z0, z1, tmax) = (2.0_f32, -1.0_f32, 1.5_f32, 300.0_f32);
    let (phi0, phi1) = ((z0 / r).asin(), (z1 / r).asin());
    for xf in placements() {
        let m = object_to_world(&xf);
        let shape = Shape::Sphere { radius: r, zmin: Some(z0), zmax: Some(z1), thetamax: tmax };
        let t = tracer(shape, xf.clone());
        for i in 0..=8 {
            for j in 0..=6 {
                let u = 0.02 + 0.96 * i as f32 / 8.0;
                let v = 0.02 + 0.96 * j as f32 / 6.0;
                let (theta, phi) = (u * tmax.to_radians(), phi0 + v * (phi1 - phi0));
                let p = r * Vec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin());
                check_point(&t, m, p, p / r, (u, v), "sphere");
            }
        }
    }
}

#[test]
fn sphere_cuts_and_sweep_miss() {
    let t = tracer(
        Shape::Sphere { radius: 2.0, zmin: Some(-1.0), zmax: Some(1.5), thetamax: 360.0 },
        vec![],
    );
    let down = Vec3::NEG_Z;
    // Through both polar holes.
    assert!(shoot(&t, Vec3::new(0.0, 0.0, 10.0), down).is_none());
    assert!(shoot(&t, Vec3::new(0.5, 0.0, 10.0), down).is_none());
    // Through the band: the upper crossing is at z = +0.62.
    let hit = shoot(&t, Vec3::new(1.9, 0.0, 10.0), down).expect("band");
    assert!(close(hit.t, 10.0 - (4.0_f32 - 1.9 * 1.9).sqrt(), REL));
    // A quarter sphere: only 0 <= theta <= 90 degrees exists.
    let t = tracer(Shape::Sphere { radius: 2.0, zmin: None, zmax: None, thetamax: 90.0 }, vec![]);
    assert!(shoot(&t, Vec3::new(10.0, -0.5, 0.0), Vec3::NEG_X).is_none(), "theta 346 and 194");
    let hit = shoot(&t, Vec3::new(10.0, 0.5, 0.0), Vec3::NEG_X).expect("theta 14");
    assert!(close(hit.t, 10.0 - 3.75_f32.sqrt(), REL));
    // Entering through the missing quarter, the ray meets the inside of the far wall.
    let hit = shoot(&t, Vec3::new(0.5, -10.0, 0.3), Vec3::Y).expect("inside of the far wall");
    let y = (4.0_f32 - 0.25 - 0.09).sqrt();
    assert!(close(hit.t, 10.0 + y, REL));
    assert!(close_v(hit.n_world, Vec3::new(0.5, y, 0.3) / 2.0, 1e-4), "outward even from inside");
}

#[test]
fn ray_from_inside_a_sphere_hits_the_far_side() {
    let t = tracer(
        Shape::Sphere { radius: 2.0, zmin: None, zmax: None, thetamax: 360.0 },
        vec![Transform::Translate([1.0, 1.0, 1.0])],
    );
    let hit = shoot(&t, Vec3::new(1.0, 1.0, 1.0), Vec3::new(0.0, 3.0, 0.0)).expect("far side");
    assert!(close(hit.t, 2.0 / 3.0, REL), "t in units of dir: {}", hit.t);
    assert!(close_v(hit.p_world, Vec3::new(1.0, 3.0, 1.0), 1e-5));
    assert!(close_v(hit.n_world, Vec3::Y, 1e-5));
}

#[test]
fn cylinder_points_hit_and_partial_sweep_misses() {
    let (r, z0, z1) = (1.5_f32, -1.0_f32, 2.0_f32);
    for xf in placements() {
        let m = object_to_world(&xf);
        let t =
            tracer(Shape::Cylinder { radius: r, zmin: z0, zmax: z1, thetamax: 270.0 }, xf.clone());
        for i in 0..=8 {
            for j in 0..=4 {
                let u = 0.02 + 0.96 * i as f32 / 8.0;
                let v = 0.02 + 0.96 * j as f32 / 4.0;
                let theta = u * 270.0_f32.to_radians();
                let n = Vec3::new(theta.cos(), theta.sin(), 0.0);
                let p = n * r + Vec3::new(0.0, 0.0, z0 + v * (z1 - z0));
                check_point(&t, m, p, n, (u, v), "cylinder");
            }
        }
    }
    let t = tracer(Shape::Cylinder { radius: 1.0, zmin: -1.0, zmax: 2.0, thetamax: 180.0 }, vec![]);
    assert!(shoot(&t, Vec3::new(-10.0, 0.0, 3.0), Vec3::X).is_none(), "above zmax");
    assert!(shoot(&t, Vec3::new(-10.0, -0.5, 0.0), Vec3::X).is_none(), "both crossings at y < 0");
    // From -y: the near crossing (theta 287) is cut, the far one (theta 73) is hit from inside.
    let hit = shoot(&t, Vec3::new(0.3, -10.0, 0.0), Vec3::Y).expect("far wall");
    let y = (1.0_f32 - 0.09).sqrt();
    assert!(close(hit.t, 10.0 + y, REL));
    assert!(close_v(hit.n_world, Vec3::new(0.3, y, 0.0), 1e-5));
}

#[test]
fn cone_points_hit_for_both_signs_of_height() {
    for height in [2.0_f32, -2.0] {
        for xf in placements() {
            let m = object_to_world(&xf);
            let t = tracer(Shape::Cone { height, radius: 1.0, thetamax: 300.0 }, xf.clone());
            for i in 0..=8 {
                for j in 0..=4 {
                    let u = 0.02 + 0.96 * i as f32 / 8.0;
                    let v = 0.02 + 0.9 * j as f32 / 4.0;
                    let theta = u * 300.0_f32.to_radians();
                    let (s, c) = theta.sin_cos();
                    let p = Vec3::new((1.0 - v) * c, (1.0 - v) * s, v * height);
                    let n =
                        Vec3::new(height.abs() * c, height.abs() * s, height.signum()).normalize();
                    check_point(&t, m, p, n, (u, v), "cone");
                }
            }
        }
    }
    let t = tracer(Shape::Cone { height: 2.0, radius: 1.0, thetamax: 360.0 }, vec![]);
    assert!(
        shoot(&t, Vec3::new(-10.0, 0.0, 3.0), Vec3::X).is_none(),
        "the other nappe is not the cone"
    );
    assert!(shoot(&t, Vec3::new(-10.0, 0.0, -0.5), Vec3::X).is_none(), "below the base");
    let t = tracer(Shape::Cone { height: 2.0, radius: 1.0, thetamax: 90.0 }, vec![]);
    assert!(shoot(&t, Vec3::new(-0.3, -0.3, 10.0), Vec3::NEG_Z).is_none(), "theta 225");
}

/// The dicer's paraboloid at `(u, v)` and its outward normal `(2x, 2y, -rmax^2 / zmax)`.
fn paraboloid(rmax: f32, z0: f32, z1: f32, tmax: f32, u: f32, v: f32) -> (Vec3, Vec3) {
    let theta = u * tmax.to_radians();
    let z = z0 + v * (z1 - z0);
    let r = rmax * (z / z1).sqrt();
    let p = Vec3::new(r * theta.cos(), r * theta.sin(), z);
    (p, Vec3::new(2.0 * p.x, 2.0 * p.y, -rmax * rmax / z1).normalize())
}

#[test]
fn paraboloid_points_hit_with_outward_normals() {
    for (z0, z1, tmax) in [(0.5_f32, 2.0_f32, 270.0_f32), (0.0, 1.5, 360.0)] {
        let rmax = 1.5;
        for xf in placements() {
            let m = object_to_world(&xf);
            let shape = Shape::Paraboloid { rmax, zmin: z0, zmax: z1, thetamax: tmax };
            let t = tracer(shape, xf.clone());
            for i in 0..=8 {
                for j in 0..=6 {
                    let u = 0.02 + 0.96 * i as f32 / 8.0;
                    let v = 0.02 + 0.96 * j as f32 / 6.0;
                    let (p, n) = paraboloid(rmax, z0, z1, tmax, u, v);
                    check_point(&t, m, p, n, (u, v), "paraboloid");
                }
            }
        }
    }
}

#[test]
fn paraboloid_cuts_and_sweep_miss() {
    // k = rmax^2 / zmax = 1.125: the surface is x^2 + y^2 = 1.125 z for 0.5 <= z <= 2.
    let k = 1.125_f32;
    let cut = |thetamax: f32| {
        tracer(Shape::Paraboloid { rmax: 1.5, zmin: 0.5, zmax: 2.0, thetamax }, vec![])
    };
    let t = cut(360.0);
    let down = Vec3::NEG_Z;
    assert!(shoot(&t, Vec3::new(-10.0, 0.0, 3.0), Vec3::X).is_none(), "above zmax");
    assert!(shoot(&t, Vec3::new(-10.0, 0.0, 0.25), Vec3::X).is_none(), "below zmin");
    // Down the axis near the apex: the surface there (z = 0.009) is cut away.
    assert!(shoot(&t, Vec3::new(0.1, 0.0, 10.0), down).is_none(), "through the bottom hole");
    // Down into the bowl: meets the inside of the wall, normal still outward.
    let hit = shoot(&t, Vec3::new(1.0, 0.5, 10.0), down).expect("inside of the wall");
    let z = 1.25 / k;
    assert!(close(hit.t, 10.0 - z, REL), "{}", hit.t);
    assert!(close_v(hit.n_world, Vec3::new(2.0, 1.0, -k).normalize(), 1e-5));
    assert!(close(hit.v, (z - 0.5) / 1.5, 1e-5));
    // From inside the bowl sideways.
    let hit = shoot(&t, Vec3::new(0.0, 0.0, 1.0), Vec3::X).expect("wall from inside");
    assert!(close(hit.t, k.sqrt(), REL) && close(hit.u, 0.0, 1e-6));
    // Far away: the quadratic stays accurate.
    let hit = shoot(&t, Vec3::new(-1.0e4, 0.0, 1.0), Vec3::X).expect("far");
    assert!(close(hit.t, 1.0e4 - k.sqrt(), 1e-6), "{}", hit.t);
    assert!(close(hit.u, 0.5, 1e-5), "theta 180 of 360");
    // A quarter sweep: theta 225 is not there, theta 27 is.
    let quarter = cut(90.0);
    assert!(shoot(&quarter, Vec3::new(-0.7, -0.7, 10.0), down).is_none(), "theta 225");
    let hit = shoot(&quarter, Vec3::new(1.0, 0.5, 10.0), down).expect("theta 27");
    assert!(close(hit.u, 0.5_f32.atan2(1.0).to_degrees() / 90.0, 1e-5));
    // Along +y at x = 0.5, z = 1: the near crossing (theta 298) is cut away, the far one
    // (theta 62) is hit from inside the bowl.
    let hit = shoot(&quarter, Vec3::new(0.5, -10.0, 1.0), Vec3::Y).expect("far wall");
    let y = (k - 0.25).sqrt();
    assert!(close(hit.t, 10.0 + y, REL), "{}", hit.t);
    // With zmin = 0 the apex is there, facing -z, hit from above and below.
    let t = tracer(Shape::Paraboloid { rmax: 1.5, zmin: 0.0, zmax: 2.0, thetamax: 360.0 }, vec![]);
    let hit = shoot(&t, Vec3::new(0.0, 0.0, 10.0), down).expect("apex from inside");
    assert!(close(hit.t, 10.0, REL) && close_v(hit.n_world, Vec3::NEG_Z, 1e-6));
    assert!(close(hit.v, 0.0, 1e-6));
    let hit = shoot(&t, Vec3::new(0.0, 0.0, -10.0), Vec3::Z).expect("apex from below");
    assert!(close(hit.t, 10.0, REL) && close_v(hit.n_world, Vec3::NEG_Z, 1e-6));
    assert!(shoot(&t, Vec3::new(0.0, 0.0, -10.0), Vec3::X).is_none(), "beside, below");
}

#[test]
fn paraboloid_hits_invert_to_the_dicer_parametrisation() {
    let (rmax, z0, z1, tmax) = (1.2_f32, 0.3_f32, 1.8_f32, 300.0_f32);
    let t = tracer(Shape::Paraboloid { rmax, zmin: z0, zmax: z1, thetamax: tmax }, vec![]);
    let mut rng = common::Rng::new(23);
    let mut hits = 0;
    for _ in 0..3_000 {
        let origin = rng.direction() * 6.0;
        let dir = rng.in_cube(1.5) + Vec3::new(0.0, 0.0, 1.0) - origin;
        let Some(h) = shoot(&t, origin, dir) else { continue };
        hits += 1;
        assert!((0.0..=1.0).contains(&h.u) && (0.0..=1.0).contains(&h.v), "{h:?}");
        let (p, n) = paraboloid(rmax, z0, z1, tmax, h.u, h.v);
        assert!(close_v(h.p_world, p, 2e-4), "{} vs {p}", h.p_world);
        assert!(close_v(h.n_world, n, 2e-3), "{} vs {n}", h.n_world);
        assert!(close_v(origin + dir * h.t, h.p_world, 2e-4));
    }
    assert!(hits > 500, "{hits}");
}

#[test]
fn disk_points_hit_facing_plus_z() {
    let (h, r) = (0.5_f32, 3.0_f32);
    for xf in placements() {
        let m = object_to_world(&xf);
        let t = tracer(Shape::Disk { height: h, radius: r, thetamax: 180.0 }, xf.clone());
        for i in 0..=6 {
            for j in 0..=4 {
                let u = 0.02 + 0.96 * i as f32 / 6.0;
                let v = 0.02 + 0.9 * j as f32 / 4.0;
                let theta = u * PI;
                let p = Vec3::new(r * (1.0 - v) * theta.cos(), r * (1.0 - v) * theta.sin(), h);
                check_point(&t, m, p, Vec3::Z, (u, v), "disk");
            }
        }
    }
    let t = tracer(Shape::Disk { height: h, radius: r, thetamax: 180.0 }, vec![]);
    let from_below = shoot(&t, Vec3::new(1.0, 1.0, -5.0), Vec3::Z).expect("from below");
    assert!(close(from_below.t, 5.5, REL) && close_v(from_below.n_world, Vec3::Z, 1e-6));
    assert!(shoot(&t, Vec3::new(1.0, -1.0, 5.0), Vec3::NEG_Z).is_none(), "theta 315");
    assert!(shoot(&t, Vec3::new(3.5, 0.1, 5.0), Vec3::NEG_Z).is_none(), "outside the radius");
    assert!(shoot(&t, Vec3::new(1.0, 1.0, 5.0), Vec3::X).is_none(), "parallel");
}

/// The torus of radii `big` and `small`, tube angles `phi` and sweep `tmax` in degrees.
fn torus_shape(big: f32, small: f32, (phimin, phimax): (f32, f32), tmax: f32) -> Shape {
    Shape::Torus { major_radius: big, minor_radius: small, phimin, phimax, thetamax: tmax }
}

/// The dicer's torus (as [`torus_shape`]) at `(u, v)` and its outward normal.
fn torus_at(big: f32, small: f32, (p0, p1): (f32, f32), tmax: f32, u: f32, v: f32) -> (Vec3, Vec3) {
    let theta = u * tmax.to_radians();
    let phi = (p0 + v * (p1 - p0)).to_radians();
    let ring = big + small * phi.cos();
    let p = Vec3::new(ring * theta.cos(), ring * theta.sin(), small * phi.sin());
    let n = Vec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin());
    (p, n)
}

#[test]
fn torus_points_hit_with_outward_normals() {
    let (big, small) = (3.0_f32, 1.0_f32);
    let (p0, p1, tmax) = (-60.0_f32, 240.0_f32, 315.0_f32);
    for xf in placements() {
        let m = object_to_world(&xf);
        let t = tracer(torus_shape(big, small, (p0, p1), tmax), xf.clone());
        for i in 0..=10 {
            for j in 0..=10 {
                let u = 0.02 + 0.96 * i as f32 / 10.0;
                let v = 0.02 + 0.96 * j as f32 / 10.0;
                let (p, n) = torus_at(big, small, (p0, p1), tmax, u, v);
                check_point(&t, m, p, n, (u, v), "torus");
            }
        }
    }
}

#[test]
fn torus_tube_range_and_sweep_cut() {
    let torus = |phimin: f32, phimax: f32, thetamax: f32| {
        tracer(torus_shape(3.0, 1.0, (phimin, phimax), thetamax), vec![])
    };
    let down = Vec3::NEG_Z;
    let upper = torus(0.0, 180.0, 360.0);
    let hit = shoot(&upper, Vec3::new(3.0, 0.0, 10.0), down).expect("top of the tube");
    assert!(close(hit.t, 9.0, REL) && close_v(hit.n_world, Vec3::Z, 1e-5));
    assert!(close(hit.v, 0.5, 1e-5));
    // The lower half only: the top is cut, the ray meets the bottom from inside.
    let lower = torus(180.0, 360.0, 360.0);
    let hit = shoot(&lower, Vec3::new(3.0, 0.0, 10.0), down).expect("bottom from inside");
    assert!(close(hit.t, 11.0, REL) && close_v(hit.n_world, Vec3::NEG_Z, 1e-5));
    // Through the hole.
    assert!(shoot(&torus(0.0, 360.0, 360.0), Vec3::new(0.0, 0.0, 10.0), down).is_none());
    // The sweep stops at 90 degrees: theta 180 is not there.
    assert!(shoot(&torus(0.0, 360.0, 90.0), Vec3::new(-3.0, 0.0, 10.0), down).is_none());
    // A grazing-free ray through the whole torus along x meets the outer wall first.
    let hit = shoot(&torus(0.0, 360.0, 360.0), Vec3::new(-10.0, 0.0, 0.0), Vec3::X).expect("outer");
    assert!(close(hit.t, 6.0, REL) && close_v(hit.n_world, Vec3::NEG_X, 1e-5));
    // Far away: the quartic stays accurate.
    let hit = shoot(&torus(0.0, 360.0, 360.0), Vec3::new(-1.0e4, 0.0, 0.5), Vec3::X).expect("far");
    let x = 3.0 + 0.75_f32.sqrt();
    assert!(close(hit.t, 1.0e4 - x, 1e-6), "{}", hit.t);
}

/// The bilinear patch at (u, v) and its outward normal dP/du x dP/dv.
fn bilinear(c: &[Vec3; 4], u: f32, v: f32) -> (Vec3, Vec3) {
    let p = c[0].lerp(c[1], u).lerp(c[2].lerp(c[3], u), v);
    let du = (c[1] - c[0]).lerp(c[3] - c[2], v);
    let dv = (c[2] - c[0]).lerp(c[3] - c[1], u);
    (p, du.cross(dv).normalize())
}

#[test]
fn bilinear_patch_points_hit() {
    let points = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.5], [0.0, 1.5, 0.8], [2.2, 1.4, -0.4]];
    let corners = points.map(Vec3::from);
    for xf in placements() {
        let m = object_to_world(&xf);
        let t = tracer(Shape::BilinearPatch { points }, xf.clone());
        for i in 0..=8 {
            for j in 0..=8 {
                let (u, v) = (0.02 + 0.96 * i as f32 / 8.0, 0.02 + 0.96 * j as f32 / 8.0);
                let (p, n) = bilinear(&corners, u, v);
                check_point(&t, m, p, n, (u, v), "bilinear");
            }
        }
    }
    let t = tracer(Shape::BilinearPatch { points }, vec![]);
    assert!(shoot(&t, Vec3::new(-0.5, 0.5, 5.0), Vec3::NEG_Z).is_none(), "beside the patch");
    // A ray in the plane of a flat patch and a ray parallel to an edge, seen edge on.
    let flat = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
    let t = tracer(Shape::BilinearPatch { points: flat }, vec![]);
    assert!(shoot(&t, Vec3::new(-1.0, 0.5, 1.0), Vec3::X).is_none());
    let hit = shoot(&t, Vec3::new(0.5, 0.0, 1.0), Vec3::new(0.0, 0.5, -1.0)).expect("oblique");
    assert!(close(hit.t, 1.0, REL) && close(hit.u, 0.5, 1e-5) && close(hit.v, 0.5, 1e-5));
}

#[test]
fn mesh_quads_and_triangles_follow_the_dicer() {
    let points = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [3.5, 1.0, 0.0],
        [3.0, 2.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let faces = Faces::from(vec![
        vec![0, 1, 2, 3],    // quad -> patch a, b, d, c (surface 0)
        vec![0, 9, 1],       // bad index: skipped
        vec![1, 4, 2],       // triangle (surface 1)
        vec![0, 1],          // too few: skipped
        vec![4, 5, 6, 7, 8], // pentagon: fan of 3 triangles (surfaces 2, 3, 4)
    ]);
    for xf in placements() {
        let m = object_to_world(&xf);
        let shape = Shape::Mesh {
            points: points.clone(),
            faces: faces.clone(),
            colors: None,
            normals: None,
            st: None,
        };
        let t = Tracer::new(&scene(vec![object(shape, xf.clone())]));
        assert_eq!(t.primitive_count(), 5);
        let up = Vec3::Z;
        // Quad: (u, v) = (x, y).
        check_point(&t, m, Vec3::new(0.25, 0.75, 0.0), up, (0.25, 0.75), "quad");
        // Triangle (1,0,0), (2,0,0), (1,1,0): at (1.25, 0.5), v = 0.5 and u = 0.25 / 0.5.
        check_point(&t, m, Vec3::new(1.25, 0.5, 0.0), up, (0.5, 0.5), "triangle");
        let hit =
            shoot(&t, m.transform_point3(Vec3::new(1.25, 0.5, 1.0)), -(m.transform_vector3(up)))
                .expect("triangle");
        assert_eq!((hit.surface, hit.face), (1, 2));
        // The fan's second triangle (4, 6, 7) = (2,0,0), (3.5,1,0), (3,2,0).
        let p = Vec3::new(2.0, 0.0, 0.0) * 0.5
            + Vec3::new(3.5, 1.0, 0.0) * 0.25
            + Vec3::new(3.0, 2.0, 0.0) * 0.25;
        check_point(
            &t,
            m,
            p,
            up,
            // Weights (0.5, 0.25, 0.25): v = 0.25, u = 0.25 / (1 - 0.25).
            (1.0 / 3.0, 0.25),
            "fan",
        );
        let hit = shoot(&t, m.transform_point3(p + up), -(m.transform_vector3(up))).expect("fan");
        assert_eq!((hit.surface, hit.face), (3, 4));
        assert!(
            shoot(&t, m.transform_point3(Vec3::new(1.8, 0.9, 1.0)), -(m.transform_vector3(up)))
                .is_none(),
            "outside the triangle"
        );
    }
}

#[test]
fn non_planar_quad_is_its_bilinear_patch() {
    let pts = [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]];
    let mesh = Shape::Mesh {
        points: pts.to_vec(),
        faces: Faces::from(vec![vec![0, 1, 2, 3]]),
        colors: None,
        normals: None,
        st: None,
    };
    let t = tracer(mesh, vec![]);
    // P0 = a, P1 = b, P2 = d, P3 = c.
    let corners = [pts[0], pts[1], pts[3], pts[2]].map(Vec3::from);
    for (u, v) in [(0.3, 0.6), (0.5, 0.5), (0.9, 0.1)] {
        let (p, n) = bilinear(&corners, u, v);
        check_point(&t, Mat4::IDENTITY, p, n, (u, v), "non-planar quad");
    }
}

#[test]
fn projective_matrix_normals_are_perpendicular_and_outward() {
    let rows =
        [[1.0, 0.0, 0.0, 0.5], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 6.0], [0.0, 0.0, 0.1, 1.0]];
    let xf = vec![Transform::Matrix(rows)];
    let m = object_to_world(&xf);
    let inv = m.inverse();
    let t = tracer(ball(), xf);
    let mut hits = 0;
    for i in 0..10 {
        for j in 0..10 {
            let target = Vec3::new(-0.6 + 0.12 * i as f32, -0.6 + 0.12 * j as f32, 0.0);
            let origin = Vec3::new(0.0, 0.0, -5.0);
            let Some(hit) = shoot(&t, origin, target - origin) else { continue };
            hits += 1;
            let q = inv.project_point3(hit.p_world);
            assert!((q.length() - 1.0).abs() < 1e-4, "on the sphere: {q}");
            let n = q.normalize();
            let (a, b) = (n.any_orthonormal_vector(), n.cross(n.any_orthonormal_vector()));
            let e = 1e-3;
            for tangent in [a, b] {
                let along = m.project_point3(q + tangent * e) - m.project_point3(q - tangent * e);
                assert!(along.normalize().dot(hit.n_world).abs() < 1e-2, "perpendicular");
            }
            let out = m.project_point3(q + n * e) - m.project_point3(q);
            assert!(out.dot(hit.n_world) > 0.0, "outward");
        }
    }
    assert!(hits > 20, "{hits}");
}

/// The first crossing of the torus implicit function along the ray that lies inside the
/// tube-angle and sweep ranges, found by marching in small steps and bisecting (`f64`).
fn torus_reference(
    o: Vec3,
    d: Vec3,
    big: f64,
    small: f64,
    phi: (f64, f64),
    tmax: f64,
) -> Option<f64> {
    let (o, d) = (o.as_dvec3(), d.as_dvec3());
    let f = |s: f64| {
        let p = o + d * s;
        let q = p.length_squared() + big * big - small * small;
        q * q - 4.0 * big * big * (p.x * p.x + p.y * p.y)
    };
    let inside = |s: f64| {
        let p = o + d * s;
        let mut theta = p.y.atan2(p.x);
        if theta < 0.0 {
            theta += std::f64::consts::TAU;
        }
        let ring = p.x.hypot(p.y);
        let a = p.z.atan2(ring - big);
        let a = phi.0 + (a - phi.0).rem_euclid(std::f64::consts::TAU);
        theta <= tmax && a <= phi.1
    };
    let steps = 40_000;
    let end = 30.0;
    let mut prev = f(0.0);
    for k in 1..=steps {
        let s = end * k as f64 / steps as f64;
        let cur = f(s);
        if (cur < 0.0) != (prev < 0.0) {
            let (mut a, mut b) = (s - end / steps as f64, s);
            for _ in 0..80 {
                let m = 0.5 * (a + b);
                if (f(m) < 0.0) == (f(a) < 0.0) { a = m } else { b = m }
            }
            if inside(a) {
                return Some(a);
            }
        }
        prev = cur;
    }
    None
}

#[test]
fn torus_agrees_with_a_marching_reference_on_random_rays() {
    let (big, small) = (2.0_f32, 0.6_f32);
    let (p0, p1, tmax) = (-30.0_f32, 200.0_f32, 290.0_f32);
    let t = tracer(torus_shape(big, small, (p0, p1), tmax), vec![]);
    let mut rng = common::Rng::new(42);
    let (mut agree, mut hits, total) = (0, 0, 2_000);
    for _ in 0..total {
        let origin = rng.direction() * rng.range(3.0, 8.0);
        let dir = (rng.in_cube(2.5) - origin).normalize();
        let reference = torus_reference(
            origin,
            dir,
            f64::from(big),
            f64::from(small),
            (f64::from(p0).to_radians(), f64::from(p1).to_radians()),
            f64::from(tmax).to_radians(),
        );
        let got = shoot(&t, origin, dir).map(|h| f64::from(h.t));
        match (got, reference) {
            (Some(a), Some(b)) if (a - b).abs() <= 1e-4 * b => {
                agree += 1;
                hits += 1;
            }
            (None, None) => agree += 1,
            _ => {}
        }
    }
    assert!(hits > 500, "{hits}");
    // Only rays grazing the tube within the marching step may disagree.
    assert!(agree >= total - 4, "{agree} of {total}");
}

#[test]
fn spawned_rays_leave_the_surface_cleanly() {
    let t = tracer(ball(), vec![Transform::Translate([100.0, 50.0, -20.0])]);
    let centre = Vec3::new(100.0, 50.0, -20.0);
    let mut rng = common::Rng::new(8);
    for _ in 0..2_000 {
        let origin = centre + rng.direction() * 5.0;
        let dir = (centre + rng.direction() * rng.range(0.0, 0.9) - origin).normalize();
        let hit = shoot(&t, origin, dir).expect("aimed inside the ball");
        // Reflected: leaves a convex surface for good.
        let reflected = dir - 2.0 * dir.dot(hit.n_world) * hit.n_world;
        assert!(t.intersect(&hit.spawn(reflected, 0.0), f32::INFINITY).is_none());
        // Transmitted straight on: meets the far side, not the entry point again.
        let inward = hit.spawn(dir, 0.0);
        let far = t.intersect(&inward, f32::INFINITY).expect("far side");
        let o = (inward.origin - centre).as_dvec3();
        let (d, b) = (dir.as_dvec3(), o.dot(dir.as_dvec3()));
        let exit = -b + (b * b - o.length_squared() + 1.0).sqrt() / d.length_squared().sqrt();
        assert!(close(far.t, exit as f32, 1e-4), "{} vs {exit}", far.t);
    }
}

#[test]
fn torus_hits_invert_to_the_dicer_parametrisation_including_spindles() {
    for (big, small) in [(3.0_f32, 1.0_f32), (1.0, 1.5)] {
        let (p0, p1, tmax) = (-90.0_f32, 200.0_f32, 330.0_f32);
        let t = tracer(torus_shape(big, small, (p0, p1), tmax), vec![]);
        let mut rng = common::Rng::new(17);
        let mut hits = 0;
        for _ in 0..3_000 {
            let origin = rng.direction() * 8.0;
            let dir = rng.in_cube(2.0) - origin;
            let Some(h) = shoot(&t, origin, dir) else { continue };
            hits += 1;
            assert!((0.0..=1.0).contains(&h.u) && (0.0..=1.0).contains(&h.v), "{h:?}");
            let (p, n) = torus_at(big, small, (p0, p1), tmax, h.u, h.v);
            assert!(close_v(h.p_world, p, 2e-4), "R {big} r {small}: {} vs {p}", h.p_world);
            assert!(close_v(h.n_world, n, 2e-3), "R {big} r {small}: {} vs {n}", h.n_world);
        }
        assert!(hits > 300, "{hits}");
    }
}

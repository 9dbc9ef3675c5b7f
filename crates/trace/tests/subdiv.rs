//! Catmull-Clark subdivision meshes: the tessellated limit surface is hit at the analytic
//! limit points of the cube, is closed (no ray escapes through a crack between patches),
//! reports the dicer's surface numbering and `(u, v)` with the limit normal there, follows
//! deformation keys and leaves holes open.

mod common;

use common::{Rng, close, deforming, object, scene, shoot};
use glam::{Vec3, Vec3Swizzles};
use reyes_scene::{Shape, SubdivTag, Transform};
use reyes_subdiv::LimitPatch;
use reyes_trace::Tracer;

/// The cube of half-side 1 about the origin (corner `i` at `(+-1, +-1, +-1)` by the bits of
/// `i`), faces wound counter-clockwise seen from outside, with these tags.
fn cube(points: Vec<[f32; 3]>, tags: Vec<SubdivTag>) -> Shape {
    let faces =
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    Shape::SubdivisionMesh {
        points,
        faces: faces.iter().map(|f| f.to_vec()).collect::<Vec<_>>().into(),
        tags,
        colors: None,
        st: None,
    }
}

fn corners(scale: f32) -> Vec<[f32; 3]> {
    (0..8)
        .map(|i| {
            let s = |bit: i32| if i & bit == 0 { -scale } else { scale };
            [s(1), s(2), s(4)]
        })
        .collect()
}

/// The cube with its corners pushed in and out, and a sharp crease along two of its edges.
fn bumped() -> Shape {
    let mut points = corners(1.0);
    for (k, p) in points.iter_mut().enumerate() {
        let f = 1.0 + 0.3 * ((k * 5 % 7) as f32 / 6.0 - 0.5);
        *p = p.map(|c| c * f);
        p[0] += 0.1 * (k % 3) as f32;
    }
    let crease = SubdivTag::Crease { vertices: vec![0, 1, 3], sharpness: 2.5 };
    let corner = SubdivTag::Corner { vertices: vec![6], sharpness: 10.0 };
    cube(points, vec![crease, corner])
}

/// The limit patches the dicer numbers its surfaces by.
fn limit(shape: &Shape) -> Vec<LimitPatch> {
    let mesh = reyes_scene::subdiv::control_mesh(shape, |_, own| own).expect("a subdivision mesh");
    reyes_subdiv::limit_patches(&mesh).expect("a valid mesh")
}

/// Limit radii of the cube (half-side 1), checked against the crate in
/// `reyes-dice`'s `a_cube_has_24_patches_facing_out_and_lies_in_its_analytic_shell`: 68/81
/// at the face centres, sqrt(3)/2 at the corners.
const FACE: f32 = 68.0 / 81.0;
const CORNER: f32 = 0.866_025_4;

/// The geometric tolerance: 1/1000 of a patch's size (the cube's patches' boxes have a
/// diagonal below 2), with f32 rounding of points of size 5 on top.
const GEOMETRIC: f32 = 2e-3 + 1e-5;

#[test]
fn the_cube_is_hit_at_its_face_centre_and_corner_limit_radii() {
    let t = Tracer::new(&scene(vec![object(cube(corners(1.0), vec![]), vec![])]));
    // Face centres and corners are tessellation vertices (corners of patches), evaluated by
    // the crate: there the hit is exact but for f32 rounding (points of size 5: 1e-5).
    let axes = [Vec3::X, Vec3::Y, Vec3::Z, Vec3::NEG_X, Vec3::NEG_Y, Vec3::NEG_Z];
    for a in axes {
        let hit = shoot(&t, a * 5.0, -a, 0.0).expect("a face centre");
        assert!(close(hit.t, 5.0 - FACE, 1e-5), "along {a}: t {}", hit.t);
        assert!(hit.n_world.dot(a) > 0.999_99, "outward normal {} at {a}", hit.n_world);
    }
    for k in 0..8 {
        let d = Vec3::from(corners(1.0)[k]).normalize();
        let hit = shoot(&t, d * 5.0, -d, 0.0).expect("a corner");
        assert!(close(hit.t, 5.0 - CORNER, 1e-5), "towards {d}: t {}", hit.t);
        assert!(hit.n_world.dot(d) > 0.999_99, "outward normal {} at {d}", hit.n_world);
    }
    // Anywhere else the surface lies between the two spheres, and the triangles within the
    // tolerance of it.
    let mut rng = Rng::new(11);
    for _ in 0..500 {
        let d = Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let Some(d) = d.try_normalize() else { continue };
        let hit = shoot(&t, d * 5.0, -d, 0.0).expect("the cube");
        let r = 5.0 - hit.t;
        assert!((FACE - GEOMETRIC..=CORNER + 1e-5).contains(&r), "radius {r} towards {d}");
        assert!(hit.surface < 24);
    }
}

#[test]
fn hits_report_the_dicer_patch_its_uv_and_the_limit_normal() {
    let shape = bumped();
    let patches = limit(&shape);
    let t = Tracer::new(&scene(vec![object(shape, vec![])]));
    let mut rng = Rng::new(5);
    let mut hits = 0;
    for _ in 0..600 {
        let d = Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let Some(d) = d.try_normalize() else { continue };
        let Some(hit) = shoot(&t, d * 6.0, -d, 0.0) else { continue };
        hits += 1;
        let patch = &patches[hit.surface as usize];
        let (p, du, dv) = patch.eval(hit.u, hit.v);
        // The hit's (u, v) is the triangle's interpolation of its vertices' (u, v), whose
        // points are on the surface: the limit point there is within a cell's second-order
        // error of the hit (a cell is at most 1/4 of a patch, chord error 1/1000 of its
        // size; the parametric offset is of the same order as the geometric one, 1e-2 of
        // the patch size 2 allows ten times that).
        assert!((p - hit.p_world).length() < 2e-2, "patch {}: {p} vs {}", hit.surface, hit.p_world);
        // Normals at the cell's corners are the limit normals there; between them they are
        // interpolated, so off the limit normal by at most the turning across one cell:
        // the bumped cube's patches turn by less than 60 degrees, a cell of at most 1/8 of
        // one by at most 7.5 degrees (cos 7.5 = 0.991); 0.99 allows the sharp crease,
        // whose normals jump across the crease edge only, never inside a patch.
        let n = du.cross(dv).normalize();
        assert!(hit.n_world.dot(n) > 0.99, "patch {}: normal {} vs {n}", hit.surface, hit.n_world);
    }
    assert!(hits > 500, "only {hits} hits");
}

#[test]
fn no_ray_escapes_a_closed_creased_mesh() {
    let t = Tracer::new(&scene(vec![object(bumped(), vec![])]));
    let centre = Vec3::new(0.1, 0.0, 0.0);
    // Many random rays from random inner points (the shared edges' vertices are
    // bit-identical on both sides: `subdivide.rs`'s unit test).
    let mut rng = Rng::new(17);
    for _ in 0..4000 {
        let origin =
            centre + Vec3::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.3), rng.range(-0.3, 0.3));
        let d = Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let Some(dir) = d.try_normalize() else { continue };
        assert!(shoot(&t, origin, dir, 0.0).is_some(), "escaped from {origin} along {dir}");
    }
}

#[test]
fn a_deforming_cube_follows_its_keys() {
    // Scaling the control points scales the limit surface (every rule is an affine
    // combination): at time s the cube of half-side 1 + s, face centre at (1 + s) 68/81.
    // The vertices of the two keys are interpolated linearly, exact at face centres.
    let shape = cube(corners(1.0), vec![]);
    let t =
        Tracer::new(&scene(vec![deforming(shape, vec![(0.0, corners(1.0)), (1.0, corners(2.0))])]));
    for time in [0.0, 0.25, 0.5, 1.0] {
        let hit = shoot(&t, Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z, time).expect("hit");
        assert!(close(hit.p_world.z, (1.0 + time) * FACE, 1e-5), "at {time}: {}", hit.p_world);
    }
}

#[test]
fn a_placed_cube_is_baked_and_a_hole_lets_rays_through() {
    let translate = vec![Transform::Translate([0.0, 0.0, 3.0])];
    // Face 1 (corners 4, 5, 7, 6) is the face at z = +1.
    let holed = cube(corners(1.0), vec![SubdivTag::Hole { faces: vec![1] }]);
    let t = Tracer::new(&scene(vec![object(holed, translate)]));
    // Through the hole at z = 3 + 68/81 to the inside of the far face, at z = 3 - 68/81.
    let hit = shoot(&t, Vec3::new(0.0, 0.0, 10.0), Vec3::NEG_Z, 0.0).expect("the far face");
    assert!(close(hit.p_world.z, 3.0 - FACE, 1e-5), "{}", hit.p_world);
    assert!(close(hit.p_object.z, -FACE, 1e-5), "{}", hit.p_object);
    assert!(hit.n_world.dot(Vec3::NEG_Z) > 0.999_99, "the far face faces out: {}", hit.n_world);
    // The other faces are still there.
    let hit = shoot(&t, Vec3::new(5.0, 0.0, 3.0), Vec3::NEG_X, 0.0).expect("a side");
    assert!(
        close(hit.p_world.x, FACE, 1e-5)
            && (hit.p_world.yz() - glam::Vec2::new(0.0, 3.0)).length() < 1e-5
    );
}

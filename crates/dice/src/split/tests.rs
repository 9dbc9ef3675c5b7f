//! The split stage's decisions: culling, splitting, dicing, and their work bounds.
use super::*;
use crate::motion::{Moment, Placement};
use crate::shapes::{Surface, surfaces};
use glam::Mat4;
use proptest::prelude::*;
use reyes_scene::{Camera, Material, Object, PatchType, Scene, Shape};
use reyes_testkit::fixtures;

/// The camera seeing a 160x120 scene of nothing from the origin down +z (fov 40, yon
/// 100) through `lens`, and its splitter (border 1, 16x16 buckets, shading rate 1,
/// grids of at most 256).
fn splitter(lens: Option<reyes_scene::Lens>) -> (CameraSetup, Splitter) {
    let camera = Camera { yon: 100.0, ..fixtures::camera([0.0; 3], [0.0, 0.0, 1.0], 40.0, lens) };
    let cam =
        CameraSetup::new(&Scene { lights: vec![], ..fixtures::scene(160, 120, camera, vec![]) });
    let frame = Frame::new(160, 120, 1, 16, 16);
    let sp = Splitter::new(&cam, &frame, 1.0, 256);
    (cam, sp)
}

/// The one surface of a whole unit sphere.
fn unit_sphere() -> Surface {
    surfaces(&shape_object(fixtures::sphere(1.0)), reyes_scene::curves::Facing::Normals).remove(0)
}

fn shape_object(shape: Shape) -> Object {
    Object::new(shape, Material::Constant { color: [1.0; 3], opacity: [1.0; 3] })
}

#[test]
fn clamp_grid_respects_the_limit() {
    assert_eq!(clamp_grid(10, 10, 256), (10, 10));
    for (nu, nv, max) in [(1000, 1000, 256), (1_000_000_000, 1, 256), (3, 500, 7), (2, 2, 1)] {
        let (a, b) = clamp_grid(nu, nv, max);
        assert!(a >= 1 && b >= 1 && u64::from(a) * u64::from(b) <= max, "{nu}x{nv} -> {a}x{b}");
    }
}

#[test]
fn split_halves_share_the_midpoint() {
    let [a, b] = Patch::root().split(true, false, 0);
    assert_eq!((a.u, b.u, a.v, b.v), ([0.0, 0.5], [0.5, 1.0], [0.0, 1.0], [0.0, 1.0]));
    let [c, d] = a.split(false, true, 0);
    assert_eq!((c.v, d.v, c.depth, c.hither_splits), ([0.0, 0.5], [0.5, 1.0], 2, 1));
    assert_eq!(Patch::at([0.25, 0.75], 7, 7), 0.75);
}

#[test]
fn patches_behind_the_eye_or_off_screen_are_culled() {
    let (_, sp) = splitter(None);
    let sphere = unit_sphere();
    let decide = |x: f32, y: f32, z: f32| decide_at(&sp, &sphere, &[Vec3::new(x, y, z)]);
    assert_eq!(decide(0.0, 0.0, -5.0), Decision::Cull);
    assert_eq!(decide(0.0, 0.0, 200.0), Decision::Cull);
    assert_eq!(decide(30.0, 0.0, 10.0), Decision::Cull);
    // Beside the eye, behind the frustum's left plane: culled by the planes.
    assert_eq!(decide(-5.0, 0.0, 0.5), Decision::Cull);
    // Around the eye: straddles hither, split.
    assert!(matches!(decide(0.0, 0.0, 0.5), Decision::Split { hither: true, .. }));
    // In view: split for size (a sphere at 10 units is about 120 pixels across).
    assert!(matches!(decide(0.0, 0.0, 10.0), Decision::Split { hither: false, .. }));
    // Far away: diced whole.
    assert!(matches!(decide(0.0, 0.0, 90.0), Decision::Dice { .. }));
}

#[test]
fn a_bezier_patch_is_bounded_by_its_control_hull() {
    // A bicubic patch folded on itself, with the fold's tip between test points: every
    // dense surface point (and every sub-patch's) lies inside the raster bound, whose
    // top is what lazy dicing waits for.
    let points: Vec<[f32; 3]> = (0..16)
        .map(|k| {
            let (i, j) = ((k % 4) as f32, (k / 4) as f32);
            let spike = if (1..3).contains(&(k % 4)) { 30.0 } else { 0.0 };
            [i - 1.5, j - 1.5 + spike * (1.0 - 2.0 * (k % 4 == 2) as i32 as f32), 20.0]
        })
        .collect();
    let shape = fixtures::patch_mesh(PatchType::Bicubic, 4, 4, points);
    let surface = surfaces(&shape_object(shape), reyes_scene::curves::Facing::Normals).remove(0);
    let (cam, sp) = splitter(None);
    let moment = Moment::new(0.0, Placement::Matrix(Mat4::IDENTITY), Mat4::IDENTITY, 0);
    let pose = Pose { surface: &surface, moment: &moment };
    for patch in [Patch::root(), Patch::root().split(true, false, 0)[1].clone()] {
        let (_, top) = sp.decide_bound(std::slice::from_ref(&pose), &patch);
        let top = top.expect("in front of the eye");
        for j in 0..=64 {
            for i in 0..=64 {
                let u = patch.u[0] + (patch.u[1] - patch.u[0]) * i as f32 / 64.0;
                let v = patch.v[0] + (patch.v[1] - patch.v[0]) * j as f32 / 64.0;
                let r = cam.eye_to_raster(surface.position(u, v));
                assert!(r.y >= top, "({u}, {v}) at raster y {} above the bound {top}", r.y);
            }
        }
    }
}

/// The decision for the whole of `surface` translated to each of `at` in turn (one
/// breakpoint per position), seen by a camera at the origin.
fn decide_at(sp: &Splitter, surface: &Surface, at: &[Vec3]) -> Decision {
    let moments: Vec<Moment> = at
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let t = k as f32 / (at.len().max(2) - 1) as f32;
            Moment::new(t, Placement::Matrix(Mat4::from_translation(*p)), Mat4::IDENTITY, 0)
        })
        .collect();
    let poses: Vec<Pose<'_>> = moments.iter().map(|moment| Pose { surface, moment }).collect();
    sp.decide(&poses, &Patch::root())
}

#[test]
fn moving_patches_are_judged_over_the_whole_shutter() {
    let (_, sp) = splitter(None);
    let sphere = unit_sphere();
    let off_left = Vec3::new(-60.0, 0.0, 60.0);
    let off_right = Vec3::new(60.0, 0.0, 60.0);
    let centre = Vec3::new(0.0, 0.0, 60.0);
    assert_eq!(decide_at(&sp, &sphere, &[off_left]), Decision::Cull);
    assert_eq!(decide_at(&sp, &sphere, &[off_left, off_left]), Decision::Cull);
    // Off screen at open, on screen at close; and across the screen in between.
    assert!(matches!(decide_at(&sp, &sphere, &[off_left, centre]), Decision::Dice { .. }));
    assert!(matches!(decide_at(&sp, &sphere, &[off_left, off_right]), Decision::Dice { .. }));
    // Depth: beyond yon at open and in view at close is kept; a segment with an end
    // behind the eye keeps the part of it in front of the eye (issue #19), so a sphere
    // passing from behind the eye to beyond yon is seen in between.
    let behind = Vec3::new(0.0, 0.0, -5.0);
    let beyond = Vec3::new(0.0, 0.0, 300.0);
    assert_eq!(decide_at(&sp, &sphere, &[behind, behind]), Decision::Cull);
    assert_eq!(decide_at(&sp, &sphere, &[beyond, beyond]), Decision::Cull);
    assert_ne!(decide_at(&sp, &sphere, &[beyond, centre]), Decision::Cull);
    assert_ne!(decide_at(&sp, &sphere, &[behind, beyond]), Decision::Cull);
    assert_ne!(decide_at(&sp, &sphere, &[behind, centre, centre]), Decision::Cull);
    // Beside the eye at both ends, behind the same side plane: culled.
    let beside = [Vec3::new(-5.0, 0.0, 0.5), Vec3::new(-6.0, 0.0, -0.5)];
    assert_eq!(decide_at(&sp, &sphere, &beside), Decision::Cull);
    // Straddling hither at any breakpoint splits for hither.
    let near = Vec3::new(0.0, 0.0, 0.5);
    assert!(matches!(
        decide_at(&sp, &sphere, &[centre, near]),
        Decision::Split { hither: true, .. }
    ));
    // The size estimate is the largest over the breakpoints.
    let (Decision::Dice { nu: nu_far, .. }, Decision::Dice { nu: nu_both, .. }) = (
        decide_at(&sp, &sphere, &[Vec3::new(0.0, 0.0, 90.0)]),
        decide_at(&sp, &sphere, &[Vec3::new(0.0, 0.0, 90.0), Vec3::new(0.0, 0.0, 60.0)]),
    ) else {
        panic!("far spheres are diced whole");
    };
    assert!(nu_both > nu_far, "{nu_both} vs {nu_far}");
}

#[test]
fn off_screen_breakpoints_ask_for_at_most_twice_the_on_screen_size() {
    let (_, sp) = splitter(None);
    let sp = Splitter { max_grid: 1 << 20, ..sp };
    let sphere = unit_sphere();
    let dice = |at: &[Vec3]| match decide_at(&sp, &sphere, at) {
        Decision::Dice { nu, nv, .. } => (nu, nv),
        other => panic!("{other:?}"),
    };
    let centre = Vec3::new(0.0, 0.0, 90.0);
    let (nu_still, nv_still) = dice(&[centre]);
    // Gone far to the side, where perspective stretches it many times over (the test
    // camera's raster scale is about 220 pixels per unit at depth 1: 40 units out at
    // depth 3 is some 2,900 pixels off screen and 30 times the size it has at depth 90).
    let (nu, nv) = dice(&[centre, Vec3::new(40.0, 0.0, 3.0)]);
    assert!(nu <= 2 * nu_still + 1 && nv <= 2 * nv_still + 1, "{nu}x{nv} vs {nu_still}x{nv_still}");
    // On screen at both ends: the larger size counts in full.
    let (nu_near, _) = dice(&[Vec3::new(0.0, 0.0, 20.0)]);
    let (nu_both, _) = dice(&[centre, Vec3::new(0.0, 0.0, 20.0)]);
    assert!(nu_near > 2 * nu_still && nu_both >= nu_near, "{nu_both} {nu_near} {nu_still}");
}

#[test]
fn a_split_that_asks_for_as_much_as_its_parent_stalls() {
    assert!(!stalls(0, 1_000), "the root has no parent to compare with");
    assert!(stalls(1_000, 1_000) && stalls(1_000, 1_001));
    assert!(!stalls(1_000, 999));
    // Saturated counts (MAX_SIDE per side) never overflow the comparison.
    let top = (MAX_SIDE as u64) * (MAX_SIDE as u64);
    assert!(stalls(top, top));
    // Two stalls in a row dice the patch, clamped and counted as limited.
    let (_, sp) = splitter(None);
    let sphere = unit_sphere();
    let at = Mat4::from_translation(Vec3::new(0.0, 0.0, 90.0));
    let moment = Moment::new(0.0, Placement::Matrix(at), Mat4::IDENTITY, 0);
    let grid = sp.test_grid(&Pose { surface: &sphere, moment: &moment }, &Patch::root());
    let root = Patch { parent_count: 1, stalls: 1, ..Patch::root() };
    let tiny = Splitter { step: 1e-9, ..sp.clone() };
    assert!(matches!(
        tiny.decide_grids_bound(std::slice::from_ref(&grid), &root).0,
        Decision::Dice { limited: true, .. }
    ));
    let fresh = Patch { parent_count: 1, stalls: 0, ..Patch::root() };
    assert!(matches!(
        tiny.decide_grids_bound(std::slice::from_ref(&grid), &fresh).0,
        Decision::Split { .. }
    ));
}

proptest! {
    /// The margin-grown bound of a patch's test points contains the raster position of
    /// every point of the patch (sampled densely), for spheres and tori anywhere in view.
    #[test]
    fn margin_bound_contains_the_patch(
        torus in any::<bool>(),
        pos in (-4.0f32..4.0, -3.0f32..3.0, 3.0f32..30.0),
        axis in (-1.0f32..1.0, -1.0f32..1.0, 0.1f32..1.0),
        angle in 0.0f32..360.0,
        u0 in 0.0f32..1.0, du in 0.01f32..1.0,
        v0 in 0.0f32..1.0, dv in 0.01f32..1.0,
        with_lens in any::<bool>(),
    ) {
        let lens = with_lens.then_some(reyes_scene::Lens { focal_length: 0.1, f_stop: 2.0, focal_distance: 8.0 });
        let (cam, sp) = splitter(lens);
        let shape = if torus {
            Shape::Torus { major_radius: 1.0, minor_radius: 0.4, phimin: 0.0, phimax: 360.0, thetamax: 360.0 }
        } else {
            Shape::Sphere { radius: 1.2, zmin: None, zmax: None, thetamax: 360.0 }
        };
        let surface = surfaces(&shape_object(shape), reyes_scene::curves::Facing::Normals).remove(0);
        let m = Mat4::from_translation(Vec3::new(pos.0, pos.1, pos.2))
            * Mat4::from_axis_angle(Vec3::new(axis.0, axis.1, axis.2).normalize(), angle.to_radians());
        let patch = Patch { u: [u0, (u0 + du).min(1.0)], v: [v0, (v0 + dv).min(1.0)], ..Patch::root() };
        let moment = Moment::new(0.0, Placement::Matrix(m), Mat4::IDENTITY, 0);
        let grid = sp.test_grid(&Pose { surface: &surface, moment: &moment }, &patch);
        let (lo, hi) = sp.margin_bound(&grid).expect("in front of the eye");
        let n = 40;
        for j in 0..=n {
            for i in 0..=n {
                let u = Patch::at(patch.u, i, n);
                let v = Patch::at(patch.v, j, n);
                let p_camera = m.project_point3(surface.position(u, v));
                let r = cam.eye_to_raster(p_camera);
                prop_assert!(r.x >= lo.x && r.y >= lo.y && r.x <= hi.x && r.y <= hi.y,
                    "{r} outside {lo}..{hi}");
            }
        }
    }
}

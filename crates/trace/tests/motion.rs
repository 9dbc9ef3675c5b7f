//! Motion: transform keys (translation, rotation along the chord, shutter normalisation,
//! a closed shutter) and deformation keys, each checked at known times.

mod common;

use common::{ball, close, close_v, deforming, moving, scene, scene_with_shutter, shoot, slide};
use glam::Vec3;
use reyes_scene::{Faces, Shape, Transform};
use reyes_trace::{Ray, Tracer};

/// The x of the near side of the unit ball sliding along x, seen from +x at `time`.
fn near_side(t: &Tracer, time: f32) -> f32 {
    shoot(t, Vec3::new(10.0, 0.0, 0.0), Vec3::NEG_X, time).expect("hit").p_world.x
}

#[test]
fn translating_sphere_is_where_its_keys_say() {
    let t = Tracer::new(&scene(vec![moving(ball(), slide(0.0, 1.0))]));
    let fwd = Vec3::Z;
    let h = shoot(&t, Vec3::new(0.0, 0.0, -10.0), fwd, 0.0).expect("time 0 at x = 0");
    assert!(close(h.t, 9.0, 1e-5) && close_v(h.p_world, Vec3::new(0.0, 0.0, -1.0), 1e-5));
    assert!(shoot(&t, Vec3::new(2.0, 0.0, -10.0), fwd, 0.0).is_none(), "not yet at x = 2");
    let h = shoot(&t, Vec3::new(2.0, 0.0, -10.0), fwd, 1.0).expect("time 1 at x = 2");
    assert!(close(h.t, 9.0, 1e-5) && close_v(h.p_world, Vec3::new(2.0, 0.0, -1.0), 1e-5));
    assert!(close_v(h.n_world, Vec3::NEG_Z, 1e-5));
    assert!(shoot(&t, Vec3::new(0.0, 0.0, -10.0), fwd, 1.0).is_none(), "gone from x = 0");
    // Along the motion: the near side is at x = 1 + 2 time.
    for (time, x) in [(0.0, 1.0), (0.25, 1.5), (0.5, 2.0), (1.0, 3.0)] {
        let near = near_side(&t, time);
        assert!(close(near, x, 1e-5), "time {time}: {near}");
        assert!(
            t.occluded(&Ray::new(Vec3::new(10.0, 0.0, 0.0), Vec3::NEG_X, time), 10.0 - x + 1e-3)
        );
        assert!(
            !t.occluded(&Ray::new(Vec3::new(10.0, 0.0, 0.0), Vec3::NEG_X, time), 10.0 - x - 1e-3)
        );
    }
}

#[test]
fn key_times_are_normalised_over_the_shutter_and_held_outside() {
    let t = Tracer::new(&scene_with_shutter(vec![moving(ball(), slide(2.5, 3.5))], 2.0, 4.0));
    // Normalised 0.25 and 0.75 are the keys; 0 and 1 hold them; 0.5 is halfway.
    for (time, x) in [(0.0, 1.0), (0.25, 1.0), (0.5, 2.0), (0.75, 3.0), (1.0, 3.0)] {
        let near = near_side(&t, time);
        assert!(close(near, x, 1e-5), "time {time}: {near}");
    }
}

#[test]
fn a_closed_shutter_uses_the_first_key() {
    let t = Tracer::new(&scene_with_shutter(vec![moving(ball(), slide(1.0, 1.0))], 1.0, 1.0));
    for time in [0.0, 0.5, 1.0] {
        assert!(close(near_side(&t, time), 1.0, 1e-5));
    }
}

#[test]
fn rotation_keys_move_points_along_the_chord() {
    // A ball at (2,0,0) turned a quarter about z. Between the keys every point moves on the
    // straight line between its key positions (as the dicer lerps world positions), so at
    // mid-shutter the centre is at (1,1,0) and the ball is squeezed to 0.707 across in xy.
    let keys = vec![
        (0.0, vec![Transform::Translate([2.0, 0.0, 0.0])]),
        (
            1.0,
            vec![
                Transform::Translate([2.0, 0.0, 0.0]),
                Transform::Rotate { angle: 90.0, axis: [0.0, 0.0, 1.0] },
            ],
        ),
    ];
    let t = Tracer::new(&scene(vec![moving(ball(), keys)]));
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let h = shoot(&t, Vec3::new(1.0, 1.0, 10.0), Vec3::NEG_Z, 0.5).expect("top");
    assert!(close(h.t, 9.0, 1e-5), "z radius stays 1: {}", h.t);
    let h = shoot(&t, Vec3::new(10.0, 1.0, 0.0), Vec3::NEG_X, 0.5).expect("side");
    assert!(close(h.p_world.x, 1.0 + half, 1e-5), "xy radius 0.707: {}", h.p_world.x);
    // The object point (1,0,0): (3,0,0) at open, (0,3,0) at close, (1.5,1.5,0) at the middle.
    let d = Vec3::new(-1.0, -1.0, 0.0).normalize();
    let h = shoot(&t, Vec3::new(10.0, 10.0, 0.0), d, 0.5).expect("diagonal");
    assert!(close_v(h.p_world, Vec3::new(1.5, 1.5, 0.0), 1e-5), "{}", h.p_world);
    assert!(close_v(h.n_world, -d, 1e-5));
    // At the keys the ball is whole.
    let h = shoot(&t, Vec3::new(0.0, 10.0, 0.0), Vec3::NEG_Y, 1.0).expect("close");
    assert!(close(h.t, 7.0, 1e-5));
}

#[test]
fn deformation_keys_move_the_points() {
    let square = |z: f32| vec![[0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z], [1.0, 1.0, z]];
    let shape = Shape::BilinearPatch {
        points: [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
    };
    let mut patch = deforming(shape, vec![(0.0, square(0.0)), (1.0, square(1.0))]);
    let t = Tracer::new(&scene(vec![patch.clone()]));
    for (time, expect) in [(0.0, 5.0), (0.5, 4.5), (1.0, 4.0)] {
        let h = shoot(&t, Vec3::new(0.25, 0.75, 5.0), Vec3::NEG_Z, time).expect("hit");
        assert!(close(h.t, expect, 1e-5), "time {time}: {}", h.t);
        assert!(close(h.u, 0.25, 1e-5) && close(h.v, 0.75, 1e-5));
        assert!(close_v(h.n_world, Vec3::Z, 1e-6));
    }
    // With transform motion as well: at mid-shutter lifted by 0.5 and moved by 0.5 in x.
    patch.motion = vec![
        reyes_scene::TransformKey { time: 0.0, transform: vec![] },
        reyes_scene::TransformKey {
            time: 1.0,
            transform: vec![Transform::Translate([1.0, 0.0, 0.0])],
        },
    ];
    let t = Tracer::new(&scene(vec![patch]));
    assert!(shoot(&t, Vec3::new(1.2, 0.5, 5.0), Vec3::NEG_Z, 0.0).is_none());
    let h = shoot(&t, Vec3::new(1.2, 0.5, 5.0), Vec3::NEG_Z, 0.5).expect("moved and lifted");
    assert!(close(h.t, 4.5, 1e-5) && close(h.u, 0.7, 1e-5));
}

#[test]
fn deforming_mesh_triangles_follow_their_vertices() {
    let pts = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let shifted: Vec<[f32; 3]> = pts.iter().map(|p| [p[0] + 3.0, p[1], p[2]]).collect();
    let shape = Shape::Mesh {
        points: pts.clone(),
        faces: Faces::from(vec![vec![0, 1, 2]]),
        colors: None,
        normals: None,
        st: None,
    };
    let t = Tracer::new(&scene(vec![deforming(shape, vec![(0.0, pts), (1.0, shifted)])]));
    let o = Vec3::new(3.2, 0.2, 1.0);
    assert!(shoot(&t, o, Vec3::NEG_Z, 0.0).is_none());
    assert!(shoot(&t, o, Vec3::NEG_Z, 0.5).is_none(), "at x 1.5..2.5");
    let h = shoot(&t, o, Vec3::NEG_Z, 1.0).expect("arrived");
    assert!(close(h.t, 1.0, 1e-6) && close(h.v, 0.2, 1e-5) && close(h.u, 0.25, 1e-5));
}

//! Odd but valid scenes: nothing panics, nothing non-finite is emitted.

mod common;

use common::*;
use reyes_scene::{Faces, Lens, Object, Shape, Transform};

fn check_finite(d: &reyes_dice::Diced) {
    for mp in &d.mpolys {
        assert!(mp.v.iter().flatten().all(|c| c.is_finite()), "{:?}", mp.v);
        assert!(mp.color.iter().flatten().all(|c| c.is_finite()), "{:?}", mp.color);
        assert!(mp.v.iter().all(|v| v[2] > 0.0));
    }
}

#[test]
fn odd_shapes_and_transforms_do_not_panic() {
    let plastic = plastic([0.8, 0.2, 0.2], 0.05);
    let shapes = vec![
        Shape::Sphere { radius: 1.0, zmin: Some(0.5), zmax: Some(-0.5), thetamax: 0.01 },
        Shape::Sphere { radius: 1.0, zmin: Some(-5.0), zmax: Some(5.0), thetamax: 360.0 },
        Shape::Cone { height: -1.0, radius: 0.5, thetamax: 360.0 },
        Shape::Torus {
            major_radius: 0.2,
            minor_radius: 1.0,
            phimin: -30.0,
            phimax: 330.0,
            thetamax: 360.0,
        },
        Shape::Disk { height: 0.0, radius: 1.0, thetamax: 360.0 },
        Shape::Cylinder { radius: 1.0, zmin: -1.0, zmax: 1.0, thetamax: 90.0 },
        Shape::BilinearPatch { points: [[0.0; 3]; 4] },
        Shape::Mesh {
            points: vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            faces: Faces::from(vec![vec![0, 1, 2], vec![0, 1, 2, 3], vec![0, 0, 0]]),
            colors: None,
            normals: None,
            st: None,
        },
    ];
    let transforms = vec![
        vec![Transform::Translate([0.0, 0.0, 5.0])],
        vec![Transform::Scale([1.0, -2.0, 0.5]), Transform::Translate([1.0, 0.0, 6.0])],
        // Singular: flattens everything onto a plane.
        vec![Transform::Matrix([
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 5.0],
            [0.0, 0.0, 0.0, 1.0],
        ])],
        // Projective: w = 1 + x/2 vanishes on the plane x = -2 through the shapes' range.
        vec![
            Transform::Translate([-2.0, 0.0, 0.0]),
            Transform::Matrix([
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
                [0.5, 0.0, 0.0, 1.0],
            ]),
            Transform::Translate([0.0, 0.0, 4.0]),
        ],
        // Around the eye.
        vec![Transform::Scale([3.0, 3.0, 3.0])],
    ];
    let mut objects = Vec::new();
    for shape in &shapes {
        for t in &transforms {
            objects.push(Object::new(shape.clone(), plastic.clone()).with_transform(t.clone()));
        }
    }
    let lens = Lens { focal_length: 0.1, f_stop: 2.0, focal_distance: 5.0 };
    for lens in [None, Some(lens)] {
        let mut s = scene(96, 64, camera_ahead(60.0, lens), objects.clone());
        s.lights.push(reyes_scene::Light::Point {
            from: [0.0, 0.0, 5.0],
            color: [1.0; 3],
            intensity: 3.0,
            shadows: false,
        });
        s.hider.max_grid_size = 1;
        s.hider.shading_rate = 8.0;
        let (d, _) = dice(&s);
        check_finite(&d);
        assert!(!d.mpolys.is_empty());
    }
}

#[test]
fn ground_plane_through_the_eye_is_cheap_and_clean() {
    let floor = Shape::BilinearPatch {
        points: [
            [-500.0, -1.0, -500.0],
            [500.0, -1.0, -500.0],
            [-500.0, -1.0, 500.0],
            [500.0, -1.0, 500.0],
        ],
    };
    let s = scene_ahead(320, 240, 45.0, vec![object(floor, vec![])]);
    let start = std::time::Instant::now();
    let (d, frame) = dice(&s);
    println!("ground plane: {:?} in {:?}", d.stats, start.elapsed());
    check_finite(&d);
    // The floor fills the lower half of the image: every pixel centre there is covered,
    // up to the horizon's last rows (far away, at yon = 1000, it is cut).
    for py in 125..240 {
        for px in 0..320 {
            let (x, y) = (px as f32 + 0.5, py as f32 + 0.5);
            assert!(covered(&d, &frame, x, y), "({px}, {py})");
        }
    }
    assert!(d.stats.micropolygons < 400_000, "{:?}", d.stats);
}

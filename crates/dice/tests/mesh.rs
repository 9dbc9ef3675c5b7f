//! Meshes: per-vertex colours reach the micropolygon vertices; flags follow the material.

mod common;

use common::*;
use glam::Vec3;
use reyes_dice::CameraSetup;
use reyes_hider::flags;
use reyes_scene::{Faces, Material, Object, Shape};

fn mesh_object(material: Material, matte: bool) -> Object {
    let shape = Shape::Mesh {
        points: quad_and_triangle(),
        faces: Faces::from(vec![vec![0, 1, 2, 3], vec![1, 4, 2]]),
        colors: Some(reyes_testkit::fixtures::five_colors()),
        normals: None,
        st: None,
    };
    Object { matte, ..Object::new(shape, material).named("mesh") }
}

#[test]
fn vertex_colours_arrive_at_the_corners() {
    let tint = [0.5, 1.0, 0.25];
    let s = scene_ahead(
        320,
        240,
        40.0,
        vec![mesh_object(Material::Constant { color: tint, opacity: [1.0; 3] }, false)],
    );
    let (d, _) = dice(&s);
    let cam = CameraSetup::new(&s);
    let Shape::Mesh { points, colors: Some(colors), .. } = &s.objects[0].shape else {
        unreachable!()
    };
    for (p, c) in points.iter().zip(colors) {
        let r = cam.eye_to_raster(Vec3::from(*p));
        let expect = Vec3::from(*c) * Vec3::from(tint);
        let mut found = 0;
        for mp in &d.mpolys {
            for k in 0..4 {
                let v = mp.v[k];
                if (v[0] - r.x).abs() < 1e-3 && (v[1] - r.y).abs() < 1e-3 {
                    let got = Vec3::from(mp.color[k]);
                    assert!(
                        (got - expect).abs().max_element() < 1e-5,
                        "vertex {p:?}: {got} vs {expect}"
                    );
                    found += 1;
                }
            }
        }
        assert!(found > 0, "no micropolygon vertex at {p:?}");
    }
    // Every colour is a blend of the vertex colours (all channels in [0, tint]).
    for mp in &d.mpolys {
        for c in &mp.color {
            assert!(c.iter().zip(tint).all(|(x, t)| *x >= -1e-6 && *x <= t + 1e-6), "{c:?}");
        }
        assert_eq!(mp.flags, flags::OPAQUE);
        assert_eq!(mp.trans, [[0.0; 3]; 4]);
        assert_eq!(mp.speed, [[0.0; 3]; 4]);
    }
    assert_eq!(d.stats.primitives, 2);
}

#[test]
fn transparency_is_premultiplied_and_matte_is_flagged() {
    let s = scene_ahead(
        320,
        240,
        40.0,
        vec![mesh_object(Material::Constant { color: [1.0; 3], opacity: [0.5, 1.0, 0.25] }, true)],
    );
    let (d, _) = dice(&s);
    assert!(!d.mpolys.is_empty());
    for mp in &d.mpolys {
        assert_eq!(mp.flags, flags::MATTE, "not opaque, matte");
        for k in 0..4 {
            assert_eq!(mp.trans[k], [0.5, 0.0, 0.75]);
            assert!(mp.color[k][0] <= 0.5 + 1e-6 && mp.color[k][2] <= 0.25 + 1e-6);
        }
    }
}

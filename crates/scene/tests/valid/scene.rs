//! The full example with every value checked, the defaults of omitted sections and fields,
//! and what the file may carry besides the scene (comments, a byte-order mark, no root name).

use reyes_scene::{
    Camera, Filter, FilterKind, Hider, Image, Lens, Material, Object, Original, Scene, Shape,
    Shutter, SpatialPattern, Transform,
};

use crate::{FULL, ok, reads_back};

#[test]
fn the_full_example_parses_with_the_expected_values() {
    let scene = ok(FULL);
    let expected = Scene {
        image: Image::new(640, 480),
        camera: Camera {
            eye: [0.0, 1.0, -10.0],
            look_at: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            projection: reyes_scene::Projection::Perspective,
            fov: 35.0,
            screen_window: None,
            hither: 0.1,
            yon: 100.0,
            shutter: Shutter::default(),
            lens: None,
            motion: vec![],
        },
        hider: Hider {
            method: reyes_scene::HiderMethod::Stochastic,
            pixel_samples: (4, 4),
            jitter: true,
            pattern: SpatialPattern::Fig6,
            time_pattern: reyes_scene::TimePattern::Fig14,
            filter: Filter { kind: FilterKind::Gaussian, width: 2.0, height: None },
            bucket_size: (16, 16),
            shading_rate: 1.0,
            seed: 0,
            max_grid_size: 256,
            flatness: 0.05,
            relative_flatness: 1.0 / 512.0,
            motion_factor: 0.0,
            focus_factor: 0.0,
            cull_back_faces: true,
            crack_free: true,
            occlusion_cull: true,
            depth_filter: reyes_scene::DepthFilter::Min,
            adaptive: reyes_scene::Adaptive::default(),
            original: Original::default(),
        },
        lights: vec![
            reyes_scene::Light::Ambient { color: [1.0, 1.0, 1.0], intensity: 0.1 },
            reyes_scene::Light::Distant {
                from: [1.0, 1.0, -1.0],
                to: [0.0, 0.0, 0.0],
                color: [1.0, 1.0, 1.0],
                intensity: 1.0,
                shadows: false,
            },
        ],
        objects: vec![
            Object::new(
                Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 },
                Material::Plastic {
                    color: [0.8, 0.1, 0.1],
                    opacity: [1.0, 1.0, 1.0],
                    ka: 1.0,
                    kd: 0.5,
                    ks: 0.5,
                    roughness: 0.1,
                    specular_color: [1.0, 1.0, 1.0],
                },
            )
            .named("ball")
            .with_transform(vec![Transform::Translate([0.0, 0.0, 0.0])]),
        ],
        solids: vec![],
        raytrace: reyes_scene::RayTrace::default(),
        outputs: Default::default(),
        texture_cache: Default::default(),
        shader_path: Vec::new(),
        shaders: Default::default(),
    };
    assert_eq!(scene, expected);
}

#[test]
fn a_thin_lens_is_written_with_some() {
    let text = FULL
        .replace("lens: None", "lens: Some((focal_length: 1.0, f_stop: 2.8, focal_distance: 8.0))");
    let scene = ok(&text);
    assert_eq!(
        scene.camera.lens,
        Some(Lens { focal_length: 1.0, f_stop: 2.8, focal_distance: 8.0 })
    );
}

#[test]
fn defaults_apply_when_sections_are_omitted() {
    let scene = ok(
        "Scene(image: (width: 8, height: 6), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)))",
    );
    assert_eq!(scene.hider, Hider::default());
    assert_eq!(scene.hider.pixel_samples, (4, 4));
    assert!(scene.hider.jitter);
    assert_eq!(scene.hider.pattern, SpatialPattern::Fig6);
    assert_eq!(scene.hider.filter, Filter { kind: FilterKind::Gaussian, width: 2.0, height: None });
    assert_eq!(scene.hider.bucket_size, (16, 16));
    assert_eq!(scene.hider.shading_rate, 1.0);
    assert_eq!(scene.hider.max_grid_size, 256);
    assert_eq!(scene.hider.original, Original::default());
    assert!(scene.lights.is_empty());
    assert!(scene.objects.is_empty());
    assert_eq!(scene.camera.up, [0.0, 1.0, 0.0]);
    assert_eq!(scene.camera.fov, 45.0);
    assert_eq!(scene.camera.hither, 0.1);
    assert_eq!(scene.camera.yon, 1000.0);
    assert_eq!(scene.camera.shutter, Shutter::default());
    assert_eq!(scene.camera.lens, None);
}

#[test]
fn partial_hider_and_object_defaults() {
    let scene = ok(r#"Scene(
        image: (width: 8, height: 6),
        camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),
        hider: (pixel_samples: (2, 3), original: (permute: true)),
        lights: [Distant(from: (0.0, 1.0, 0.0)), Point(from: (1.0, 2.0, 3.0))],
        objects: [(shape: Disk(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)))],
    )"#);
    assert_eq!(scene.hider.pixel_samples, (2, 3));
    assert_eq!(scene.hider.bucket_size, (16, 16));
    assert!(scene.hider.original.permute && !scene.hider.original.jitter_tables);
    assert_eq!(
        scene.lights[0],
        reyes_scene::Light::Distant {
            from: [0.0, 1.0, 0.0],
            to: [0.0, 0.0, 0.0],
            color: [1.0, 1.0, 1.0],
            intensity: 1.0,
            shadows: false,
        }
    );
    let object = &scene.objects[0];
    assert_eq!(object.name, "");
    assert!(object.transform.is_empty());
    assert!(!object.matte);
    assert_eq!(object.shape, Shape::Disk { height: 0.0, radius: 1.0, thetamax: 360.0 });
    assert_eq!(
        object.material,
        Material::Matte { color: [0.5, 0.5, 0.5], opacity: [1.0, 1.0, 1.0], ka: 1.0, kd: 1.0 }
    );
}

#[test]
fn comments_byte_order_mark_and_anonymous_root_are_accepted() {
    let text = "\u{feff}// a scene\n(/* no name */ image: (width: 8, height: 6),\n camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)))";
    assert_eq!(ok(text).image, Image::new(8, 6));
}

#[test]
fn what_ron_writes_reads_back() {
    let scene = ok(FULL);
    reads_back(&scene);
}

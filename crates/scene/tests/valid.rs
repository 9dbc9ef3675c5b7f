//! Valid scenes parse to the expected values, defaults fill omitted sections, and `load`
//! reports unreadable and bad files with the right error kind and exit code.

mod common;

use std::path::Path;

use common::{load_bad, temp_file};

use reyes_scene::{
    Camera, CameraKey, Csg, Filter, FilterKind, Hider, Image, Interpolation, Lens, LoadError,
    Material, Object, Original, PointsKey, Scene, Shape, Shutter, ShutterShape, Solid,
    SpatialPattern, Transform, TransformKey, load, parse,
};

/// The full example of the task and of docs/scene-format.md.
const FULL: &str = r#"
Scene(
  image: (width: 640, height: 480),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0),
           fov: 35.0, hither: 0.1, yon: 100.0, shutter: (open: 0.0, close: 1.0), lens: None),
  hider: (pixel_samples: (4, 4), jitter: true, filter: (kind: Gaussian, width: 2.0),
          bucket_size: (16, 16), shading_rate: 1.0, seed: 0),
  lights: [Ambient(color: (1.0, 1.0, 1.0), intensity: 0.1),
           Distant(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), color: (1.0, 1.0, 1.0), intensity: 1.0)],
  objects: [(name: "ball", shape: Sphere(radius: 1.0), transform: [Translate((0.0, 0.0, 0.0))],
             material: Plastic(color: (0.8, 0.1, 0.1), opacity: (1.0, 1.0, 1.0)))],
)
"#;

fn ok(text: &str) -> Scene {
    parse(text, Path::new("test.ron")).unwrap_or_else(|e| panic!("{e}"))
}

/// What ron writes for `scene` parses back to `scene`.
fn reads_back(scene: &Scene) {
    let text = ron::ser::to_string_pretty(scene, ron::ser::PrettyConfig::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(&ok(&text), scene);
}

/// An `f32` vector of the scene in `f64`.
fn dvec(a: &[f32; 3]) -> glam::DVec3 {
    glam::DVec3::new(f64::from(a[0]), f64::from(a[1]), f64::from(a[2]))
}

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

/// Every kind of motion at once: a moving camera, a gradual shutter, an object with three
/// transform keys, a deforming mesh and a deforming patch, and the new `original` switches.
const MOTION: &str = r#"
Scene(
  image: (width: 160, height: 120),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0),
           shutter: (open: 0.0, close: 1.0, shape: Gradual(ramp: 0.25)),
           motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)),
                    (time: 1.0, eye: (1.0, 1.0, -10.0), look_at: (1.0, 0.0, 0.0), up: (0.1, 1.0, 0.0))]),
  hider: (original: (time_pairing: true, lens: true, moving_clip: true)),
  objects: [
    (name: "spinner", shape: Sphere(radius: 1.0), material: Matte(color: (0.8, 0.1, 0.1)),
     transform: [Translate((0.0, 0.0, 0.0))],
     motion: [
       (time: 0.0, transform: [Translate((-1.0, 0.0, 0.0))]),
       (time: 0.5, transform: [Rotate(angle: 45.0, axis: (0.0, 1.0, 0.0)), Translate((0.0, 0.5, 0.0))]),
       (time: 1.0, transform: [Scale((1.0, 2.0, 1.0)), Translate((1.0, 0.0, 0.0))]),
     ]),
    (name: "wobble",
     shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]),
     material: Matte(color: (0.1, 0.8, 0.1)),
     deform: [(time: 0.25, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]),
              (time: 0.75, points: [(0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (0.0, 1.5, 0.0)])]),
    (name: "flag",
     shape: BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))),
     material: Matte(color: (0.1, 0.1, 0.8)),
     deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]),
              (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.5), (0.0, 1.0, 0.0), (1.0, 1.0, -0.5)])]),
  ],
)
"#;

#[test]
fn motion_parses_with_the_expected_values() {
    let scene = ok(MOTION);
    let cam = &scene.camera;
    assert_eq!(
        cam.shutter,
        Shutter { open: 0.0, close: 1.0, shape: ShutterShape::Gradual { ramp: 0.25 } }
    );
    assert_eq!(
        cam.motion,
        vec![
            CameraKey {
                time: 0.0,
                eye: [0.0, 1.0, -10.0],
                look_at: [0.0, 0.0, 0.0],
                up: [0.0, 1.0, 0.0]
            },
            CameraKey {
                time: 1.0,
                eye: [1.0, 1.0, -10.0],
                look_at: [1.0, 0.0, 0.0],
                up: [0.1, 1.0, 0.0]
            },
        ]
    );
    let original = scene.hider.original;
    assert!(original.time_pairing && original.lens && original.moving_clip);
    assert!(!original.permute && !original.matte);

    let spinner = &scene.objects[0];
    assert_eq!(spinner.motion.len(), 3);
    assert_eq!(
        spinner.motion[1],
        TransformKey {
            time: 0.5,
            transform: vec![
                Transform::Rotate { angle: 45.0, axis: [0.0, 1.0, 0.0] },
                Transform::Translate([0.0, 0.5, 0.0]),
            ],
        }
    );
    assert_eq!(spinner.motion.iter().map(|k| k.time).collect::<Vec<_>>(), [0.0, 0.5, 1.0]);
    assert!(spinner.deform.is_empty());

    let wobble = &scene.objects[1];
    assert!(wobble.motion.is_empty());
    assert_eq!(
        wobble.deform[1],
        PointsKey { time: 0.75, points: vec![[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.5, 0.0]] }
    );
    let flag = &scene.objects[2];
    assert_eq!(flag.deform.len(), 2);
    assert_eq!(flag.deform[1].points[3], [1.0, 1.0, -0.5]);
}

#[test]
fn motion_defaults_to_none() {
    let scene = ok(FULL);
    assert_eq!(scene.camera.shutter.shape, ShutterShape::Uniform);
    assert!(scene.camera.motion.is_empty());
    let original = scene.hider.original;
    assert!(!original.time_pairing && !original.lens && !original.moving_clip);
    assert!(scene.objects.iter().all(|o| o.motion.is_empty() && o.deform.is_empty()));
}

#[test]
fn motion_reads_back_from_what_ron_writes() {
    let scene = ok(MOTION);
    reads_back(&scene);
}

#[test]
fn a_gradual_shutter_accepts_ramps_up_to_one_half() {
    for ramp in ["0.5", "0.001", "0.25"] {
        let text = MOTION.replace("ramp: 0.25", &format!("ramp: {ramp}"));
        let expected = ramp.parse::<f32>().unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(ok(&text).camera.shutter.shape, ShutterShape::Gradual { ramp: expected });
    }
    let text = MOTION.replace("shape: Gradual(ramp: 0.25)", "shape: Uniform");
    assert_eq!(ok(&text).camera.shutter.shape, ShutterShape::Uniform);
}

#[test]
fn keys_may_sit_on_a_shifted_or_closed_shutter() {
    // Keys exactly at both ends of a shutter that does not start at 0.
    let shifted = MOTION
        .replace("open: 0.0, close: 1.0", "open: 2.0, close: 3.0")
        .replace("time: 0.0,", "time: 2.0,")
        .replace("time: 0.25,", "time: 2.25,")
        .replace("time: 0.5,", "time: 2.5,")
        .replace("time: 0.75,", "time: 2.75,")
        .replace("time: 1.0,", "time: 3.0,");
    let scene = ok(&shifted);
    assert_eq!(scene.camera.motion[1].time, 3.0);
    // A closed shutter (no motion blur): every key at the opening time.
    let closed = "Scene(image: (width: 8, height: 8),
      camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), shutter: (open: 0.5, close: 0.5),
               motion: [(time: 0.5, eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),
                        (time: 0.5, eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0))]),
      objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
                 motion: [(time: 0.5, transform: []), (time: 0.5, transform: [])])])";
    let scene = ok(closed);
    assert_eq!(scene.objects[0].motion.len(), 2);
}

#[test]
fn load_reads_a_valid_file() {
    let path = temp_file("valid.ron", FULL.as_bytes());
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene, ok(FULL));
}

#[test]
fn load_reports_an_unreadable_file_with_exit_code_1() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-such-dir/missing.ron");
    let err = load(&path).err().unwrap_or_else(|| panic!("loaded a missing file"));
    assert!(matches!(err, LoadError::Io { .. }), "{err:?}");
    assert_eq!(err.exit_code(), 1);
    let shown = err.to_string();
    assert!(shown.starts_with(&format!("{}: cannot read the scene file: ", path.display())));
    assert!(!shown.contains('\n'));
}

#[test]
fn load_reports_a_bad_scene_with_exit_code_2() {
    let path = temp_file("bad.ron", FULL.replace("radius: 1.0", "radius: -1.0").as_bytes());
    let err = load_bad(&path);
    let LoadError::Scene(scene_err) = &err else { panic!("{err:?}") };
    assert_eq!(scene_err.file, path);
    assert_eq!(scene_err.field, "objects[0].shape.radius");
    assert_eq!((scene_err.line, scene_err.col), (Some(10), Some(50)));
    assert_eq!(err.to_string(), scene_err.to_string());
}

#[test]
fn load_reports_invalid_utf8_as_a_bad_scene() {
    let mut bytes = b"Scene(\n  image: (width: 8, hei".to_vec();
    bytes.push(0xff);
    let path = temp_file("latin1.ron", &bytes);
    let err = load_bad(&path);
    let LoadError::Scene(e) = err else { panic!("not a scene error") };
    assert_eq!((e.line, e.col), (Some(2), Some(24)));
    assert_eq!(e.message, "the file is not valid UTF-8");
}

/// Constructive solid geometry: a sphere minus a cylinder, a lens (intersection of two
/// spheres), a 3-deep nested tree, a closed cube mesh, and glass and Gouraud objects.
const CSG: &str = r#"
Scene(
  image: (width: 160, height: 120),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)),
  hider: (original: (csg_order: true)),
  lights: [Ambient(intensity: 0.2), Distant(from: (1.0, 1.0, -1.0))],
  objects: [
    (name: "ball", shape: Sphere(radius: 1.0), material: Plastic(color: (0.8, 0.1, 0.1)),
     interpolation: Gouraud),
    (name: "hole", shape: Cylinder(radius: 0.4, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.8, 0.8, 0.1))),
    (name: "left", shape: Sphere(radius: 2.0), transform: [Translate((-1.5, 0.0, 0.0))],
     material: Plastic(color: (0.9, 0.9, 0.9), opacity: (0.3, 0.3, 0.3)), glass: Some(0.25)),
    (name: "right", shape: Sphere(radius: 2.0, zmin: Some(-2.0), zmax: Some(3.0)),
     transform: [Translate((1.5, 0.0, 0.0))],
     material: Plastic(color: (0.9, 0.9, 0.9), opacity: (0.3, 0.3, 0.3)), glass: Some(0.25)),
    (name: "cube",
     shape: Mesh(points: [(-1.0, -1.0, -1.0), (1.0, -1.0, -1.0), (1.0, 1.0, -1.0), (-1.0, 1.0, -1.0),
                          (-1.0, -1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, 1.0), (-1.0, 1.0, 1.0)],
                 faces: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]]),
     material: Matte(color: (0.2, 0.2, 0.8))),
    (name: "ring", shape: Torus(major_radius: 1.0, minor_radius: 0.3, phimin: -90.0, phimax: 270.0),
     material: Matte(color: (0.2, 0.8, 0.2))),
    (name: "cone", shape: Cone(height: 2.0, radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5)),
     motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Translate((0.0, 1.0, 0.0))])]),
    (name: "pip", shape: Sphere(radius: 0.2), material: Matte(color: (0.5, 0.5, 0.5))),
    (name: "floor", shape: Disk(radius: 5.0), material: Matte(color: (0.5, 0.5, 0.5)), glass: Some(1.0)),
    (name: "floor", shape: Disk(radius: 6.0), material: Matte(color: (0.5, 0.5, 0.5)), glass: Some(0.0)),
    (shape: Disk(radius: 7.0), material: Matte(color: (0.5, 0.5, 0.5))),
    (shape: Disk(radius: 8.0), material: Matte(color: (0.5, 0.5, 0.5))),
  ],
  solids: [
    (name: "drilled", tree: Difference(Object("ball"), Object("hole"))),
    (name: "lens", tree: Intersection([Object("left"), Object("right")])),
    (name: "nested",
     tree: Difference(Union([Object("cube"), Intersection([Object("ring"), Object("cone")])]), Object("pip"))),
  ],
)
"#;

#[test]
fn csg_parses_with_the_expected_values() {
    let scene = ok(CSG);
    let object = |name: &str| Csg::Object(name.into());
    assert_eq!(
        scene.solids,
        vec![
            Solid {
                name: "drilled".into(),
                tree: Csg::Difference(Box::new(object("ball")), Box::new(object("hole"))),
            },
            Solid {
                name: "lens".into(),
                tree: Csg::Intersection(vec![object("left"), object("right")]),
            },
            Solid {
                name: "nested".into(),
                tree: Csg::Difference(
                    Box::new(Csg::Union(vec![
                        object("cube"),
                        Csg::Intersection(vec![object("ring"), object("cone")]),
                    ])),
                    Box::new(object("pip")),
                ),
            },
        ]
    );
    assert!(scene.hider.original.csg_order);
    assert_eq!(scene.objects[0].interpolation, Interpolation::Gouraud);
    assert_eq!(scene.objects[1].interpolation, Interpolation::Flat);
    assert_eq!(scene.objects[2].glass, Some(0.25));
    assert_eq!(scene.objects[1].glass, None);
    assert_eq!((scene.objects[8].glass, scene.objects[9].glass), (Some(1.0), Some(0.0)));
}

#[test]
fn csg_defaults_to_nothing() {
    let scene = ok(FULL);
    assert!(scene.solids.is_empty());
    assert!(!scene.hider.original.csg_order);
    assert_eq!(scene.objects[0].interpolation, Interpolation::Flat);
    assert_eq!(scene.objects[0].glass, None);
}

#[test]
fn csg_reads_back_from_what_ron_writes() {
    let scene = ok(CSG);
    reads_back(&scene);
}

/// More closed operands: n-ary trees, sphere cuts at or beyond the poles, a deforming closed
/// mesh, triangles and a quad with a repeated corner.
#[test]
fn closed_operands_are_accepted() {
    let tetra = "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)],
                      faces: [[0, 2, 1, 1], [0, 1, 3], [0, 0, 3, 2], [1, 2, 3], [3, 3, 3]])";
    let text = format!(
        r#"Scene(
      image: (width: 8, height: 8),
      camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),
      objects: [
        (name: "a", shape: Sphere(radius: 1.0, zmin: Some(-1.0), zmax: Some(1.0), thetamax: 360.0),
         material: Matte(color: (0.5, 0.5, 0.5))),
        (name: "b", shape: Sphere(radius: 1.0, zmin: Some(-5.0), zmax: Some(5.0)),
         material: Matte(color: (0.5, 0.5, 0.5))),
        (name: "c", shape: {tetra}, material: Matte(color: (0.5, 0.5, 0.5)),
         deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]),
                  (time: 1.0, points: [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0), (0.0, 0.0, 2.0)])]),
        (name: "d", shape: Cylinder(radius: 1.0, zmin: 0.0, zmax: 1.0, thetamax: 360.0),
         material: Matte(color: (0.5, 0.5, 0.5))),
        (name: "e", shape: Torus(major_radius: 2.0, minor_radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5))),
      ],
      solids: [
        (tree: Union([Object("a"), Object("b"), Object("c")])),
        (tree: Intersection([Object("d"), Object("e")])),
      ],
    )"#
    );
    let scene = ok(&text);
    assert_eq!(scene.solids.len(), 2);
    assert_eq!(scene.solids[0].name, "");
}

// ---- Distributed ray tracing fields and rolling ----

/// Every new field of distributed ray tracing, with defaults left out where they exist.
const TRACED: &str = r#"
Scene(
  image: (width: 64, height: 48),
  camera: (eye: (0.0, 2.0, -10.0), look_at: (0.0, 1.0, 0.0)),
  lights: [
    Point(from: (0.0, 5.0, 0.0), shadows: true),
    Distant(from: (1.0, 1.0, -1.0), shadows: true),
    Area(shape: Sphere(center: (0.0, 8.0, 0.0), radius: 1.0)),
    Area(shape: Disk(center: (2.0, 8.0, 0.0), normal: (0.0, -1.0, 0.0), radius: 0.5),
         color: (1.0, 0.9, 0.8), intensity: 30.0),
    Area(shape: Rectangle(corner: (-1.0, 9.0, -1.0), edge_u: (2.0, 0.0, 0.0), edge_v: (0.0, 0.0, 2.0)),
         motion: [(time: 0.0), (time: 1.0, offset: (1.0, 0.0, 0.0), intensity: 0.5)]),
  ],
  objects: [
    (name: "mirror", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
     reflect: Some((color: (0.9, 0.9, 0.9)))),
    (name: "glass", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
     refract: Some((ior: 1.5))),
    (name: "ball", shape: Sphere(radius: 0.5), material: Plastic(color: (1.0, 1.0, 1.0)),
     pattern: Some(PoolBall(color: (0.9, 0.7, 0.1))),
     roll: Some((radius: 0.5, path: [(time: 0.0, position: (-1.0, 0.5, 0.0)), (time: 1.0, position: (1.0, 0.5, 0.0))]))),
  ],
)
"#;

#[test]
fn ray_tracing_fields_take_their_defaults() {
    use reyes_scene::{
        AreaShape, HiderMethod, Light, LightKey, Pattern, RayTrace, Reflect, Refract,
    };
    let scene = ok(TRACED);
    assert_eq!(scene.hider.method, HiderMethod::Stochastic);
    assert_eq!(scene.raytrace, RayTrace { max_depth: 4, min_weight: 0.01, vertex_rays: 1 });
    assert_eq!(scene.raytrace, RayTrace::default());
    let plain = ok(FULL);
    assert!(plain.lights.iter().all(|l| match l {
        Light::Distant { shadows, .. } | Light::Point { shadows, .. } => !shadows,
        _ => true,
    }));
    assert!(matches!(scene.lights[0], Light::Point { shadows: true, .. }));
    assert_eq!(
        scene.lights[2],
        Light::Area {
            shape: AreaShape::Sphere { center: [0.0, 8.0, 0.0], radius: 1.0 },
            color: [1.0, 1.0, 1.0],
            intensity: 1.0,
            motion: vec![],
        }
    );
    let Light::Area { motion, .. } = &scene.lights[4] else { panic!("not an area light") };
    assert_eq!(
        motion,
        &[
            LightKey { time: 0.0, offset: [0.0, 0.0, 0.0], intensity: 1.0 },
            LightKey { time: 1.0, offset: [1.0, 0.0, 0.0], intensity: 0.5 },
        ]
    );
    assert_eq!(scene.objects[0].reflect, Some(Reflect { color: [0.9, 0.9, 0.9], gloss: 0.0 }));
    assert_eq!(
        scene.objects[1].refract,
        Some(Refract { ior: 1.5, color: [1.0, 1.0, 1.0], blur: 0.0 })
    );
    assert_eq!(
        scene.objects[2].pattern,
        Some(Pattern::PoolBall { color: [0.9, 0.7, 0.1], striped: false })
    );
    let roll = scene.objects[2].roll.as_ref().unwrap_or_else(|| panic!("no roll"));
    assert_eq!((roll.up, roll.steps), ([0.0, 1.0, 0.0], 8));
    // Nothing of it is in the plain scene.
    assert!(plain.objects.iter().all(|o| o.reflect.is_none()
        && o.refract.is_none()
        && o.pattern.is_none()
        && o.roll.is_none()));
}

#[test]
fn limits_at_their_ends_are_accepted() {
    let with = |hider: &str, raytrace: &str, mirror: &str| {
        TRACED
            .replacen(
                "  lights: [",
                &format!("  hider: ({hider}),\n  raytrace: ({raytrace}),\n  lights: ["),
                1,
            )
            .replacen("reflect: Some((color: (0.9, 0.9, 0.9)))", mirror, 1)
    };
    let scene = ok(&with(
        "method: RayTrace",
        "max_depth: 64, min_weight: 0.0, vertex_rays: 4096",
        "reflect: Some((color: (1.0, 0.0, 1.0), gloss: 89.9))",
    ));
    assert_eq!(scene.hider.method, reyes_scene::HiderMethod::RayTrace);
    assert_eq!(scene.raytrace.vertex_rays, 4096);
    // A depth limit of zero is fine when no object asks for reflection or refraction rays.
    let text = with("", "max_depth: 0, min_weight: 0.999", "matte: false").replacen(
        ",\n     refract: Some((ior: 1.5))",
        "",
        1,
    );
    assert_eq!(ok(&text).raytrace.max_depth, 0);
}

/// The object-to-world matrix of a transform list, as the dicer builds it (first item first),
/// in `f64`.
fn matrix(list: &[Transform]) -> glam::DMat4 {
    use glam::DMat4;
    list.iter().fold(DMat4::IDENTITY, |m, t| {
        let step = match t {
            Transform::Translate(d) => DMat4::from_translation(dvec(d)),
            Transform::Rotate { angle, axis } => {
                DMat4::from_axis_angle(dvec(axis).normalize(), f64::from(*angle).to_radians())
            }
            Transform::Scale(s) => DMat4::from_scale(dvec(s)),
            Transform::Matrix(rows) => {
                DMat4::from_cols_array_2d(&rows.map(|r| r.map(f64::from))).transpose()
            }
        };
        step * m
    })
}

/// A ball of radius 0.5 on a plane tilted 30 degrees about x, rolling along an L-shaped path
/// (two segments at right angles, then back), with a rest orientation.
fn rolling(steps: u32) -> String {
    let tilt = 30f64.to_radians();
    let up = [0.0, tilt.cos(), -tilt.sin()];
    let across = [1.0, 0.0, 0.0];
    let along = [0.0, tilt.sin(), tilt.cos()];
    let at = |a: f64, b: f64| {
        let p: Vec<String> = (0..3)
            .map(|k| format!("{:?}", (0.5 * up[k] + a * across[k] + b * along[k]) as f32))
            .collect();
        format!("({})", p.join(", "))
    };
    format!(
        "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 2.0, -10.0), look_at: (0.0, 0.0, 0.0)),
         objects: [(name: \"ball\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5)),
           transform: [Rotate(angle: 70.0, axis: (1.0, 2.0, 0.5)), Scale((1.0, 1.0, 1.0))],
           roll: Some((radius: 0.5, up: ({:?}, {:?}, {:?}), steps: {steps},
             path: [(time: 0.0, position: {}), (time: 0.4, position: {}), (time: 0.7, position: {}),
                    (time: 1.0, position: {})])))])",
        up[0] as f32,
        up[1] as f32,
        up[2] as f32,
        at(0.0, 0.0),
        at(1.2, 0.0),
        at(1.2, 0.9),
        at(0.3, 0.3),
    )
}

#[test]
fn rolling_expands_into_transform_keys() {
    let scene = ok(&rolling(4));
    let ball = &scene.objects[0];
    let roll = ball.roll.as_ref().unwrap_or_else(|| panic!("the roll is kept"));
    // One key at the start and `steps` per segment, times strictly increasing.
    assert_eq!(ball.motion.len(), 1 + 3 * 4);
    let times: Vec<f32> = ball.motion.iter().map(|k| k.time).collect();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    assert_eq!((times[0], times[4], times[8], times[12]), (0.0, 0.4, 0.7, 1.0));
    assert!((times[2] - 0.2).abs() < 1e-6);
    for (k, key) in ball.motion.iter().enumerate() {
        // The rest orientation comes first, the centre last.
        assert_eq!(key.transform[..2], ball.transform[..], "key {k}");
        assert!(matches!(key.transform.last(), Some(Transform::Translate(_))), "key {k}");
        // At most: rest, finished turns, current turn, translation.
        assert!(key.transform.len() <= ball.transform.len() + 3, "key {k}");
        let m = matrix(&key.transform);
        // The ball's centre (the object's origin) is on the path ...
        let segment = (k.saturating_sub(1) / 4).min(2);
        let f = if k == 0 { 0.0 } else { ((k - 1) % 4 + 1) as f64 / 4.0 };
        let p = |i: usize| dvec(&roll.path[i].position);
        let expected = p(segment) + (p(segment + 1) - p(segment)) * f;
        let centre = m.transform_point3(glam::DVec3::ZERO);
        assert!((centre - expected).length() < 1e-5, "key {k}: {centre} vs {expected}");
        // ... and the ball turns rigidly about it.
        for q in [glam::DVec3::X, glam::DVec3::new(0.3, -0.2, 0.4)] {
            let rest = matrix(&ball.transform).transform_point3(q).length();
            assert!(((m.transform_point3(q) - centre).length() - rest).abs() < 1e-5);
        }
    }
    // The first segment (2.4 radii) turns the ball 137.5 degrees in all.
    let turned = |k: usize| {
        ball.motion[k].transform.iter().fold(0.0f32, |sum, t| match t {
            Transform::Rotate { angle, .. } if !ball.transform.contains(t) => sum + angle,
            _ => sum,
        })
    };
    assert!((turned(4) - 137.509_87).abs() < 1e-3, "{}", turned(4));
    assert!((turned(2) - 68.754_93).abs() < 1e-3, "{}", turned(2));
}

/// Rolling without slipping: the material point at the bottom of the ball (the contact
/// point, `centre - radius * up`) is instantaneously at rest. At each key strictly inside a
/// segment, the central difference over the neighbouring keys of where the engines put that
/// material point (the keys' matrices, linearly interpolated) is ~0, while the centre moves;
/// its error is second order in the step angle, so it shrinks as the steps get finer. The
/// opposite turn would move the contact point at twice the centre's speed.
#[test]
fn the_contact_point_does_not_slip() {
    let mut worst = Vec::new();
    for steps in [8, 32, 128] {
        let scene = ok(&rolling(steps));
        let ball = &scene.objects[0];
        let roll = ball.roll.as_ref().unwrap_or_else(|| panic!("no roll"));
        let up = dvec(&roll.up).normalize();
        let radius = f64::from(roll.radius);
        let keys = &ball.motion;
        let mut ratio: f64 = 0.0;
        let mut flipped: f64 = f64::INFINITY;
        let steps = steps as usize;
        for k in 1..keys.len() - 1 {
            if k % steps == 0 {
                continue; // a corner of the path: the velocity changes there
            }
            let (before, here, after) = (
                matrix(&keys[k - 1].transform),
                matrix(&keys[k].transform),
                matrix(&keys[k + 1].transform),
            );
            let dt = f64::from(keys[k + 1].time - keys[k - 1].time);
            let centre = here.transform_point3(glam::DVec3::ZERO);
            let contact = here.inverse().transform_point3(centre - up * radius);
            let velocity =
                (after.transform_point3(contact) - before.transform_point3(contact)) / dt;
            let centre_velocity = (after.transform_point3(glam::DVec3::ZERO)
                - before.transform_point3(glam::DVec3::ZERO))
                / dt;
            assert!(centre_velocity.length() > 1.0, "key {k}: the ball should be moving");
            ratio = ratio.max(velocity.length() / centre_velocity.length());
            // The top of the ball moves at twice the centre's speed, in its direction.
            let top = here.inverse().transform_point3(centre + up * radius);
            let top_velocity = (after.transform_point3(top) - before.transform_point3(top)) / dt;
            assert!(
                (top_velocity - centre_velocity * 2.0).length() < 0.1 * centre_velocity.length()
            );
            // Rolling the other way would drag the contact point at twice the centre's speed.
            flipped =
                flipped.min((centre_velocity * 2.0 - velocity).length() / centre_velocity.length());
        }
        assert!(flipped > 1.5, "steps {steps}: {flipped}");
        worst.push(ratio);
    }
    // Step angles of about 17, 4.3 and 1.1 degrees: relative error ~ angle^2 / 6.
    assert!(worst[0] < 0.02 && worst[1] < 2e-3 && worst[2] < 2e-4, "{worst:?}");
    assert!(worst[0] > worst[1] && worst[1] > worst[2], "{worst:?}");
    eprintln!("contact speed / centre speed at 8, 32, 128 steps per segment: {worst:?}");
}

#[test]
fn a_rolled_scene_reads_back_from_what_ron_writes() {
    let scene = ok(&rolling(8));
    assert!(!scene.objects[0].motion.is_empty() && scene.objects[0].roll.is_some());
    // The written motion is exactly what the roll expands to, so it is accepted with it.
    reads_back(&scene);
    reads_back(&ok(TRACED));
}

/// A closed shutter: every path key at `open`, the ball held at its first position.
#[test]
fn rolling_under_a_closed_shutter() {
    let text = TRACED
        .replacen(
            "look_at: (0.0, 1.0, 0.0))",
            "look_at: (0.0, 1.0, 0.0), shutter: (open: 0.5, close: 0.5))",
            1,
        )
        .replacen("(time: 0.0, position", "(time: 0.5, position", 1)
        .replacen("(time: 1.0, position", "(time: 0.5, position", 1)
        .replacen("motion: [(time: 0.0), (time: 1.0,", "motion: [(time: 0.5), (time: 0.5,", 1);
    let scene = ok(&text);
    let keys = &scene.objects[2].motion;
    assert_eq!(keys.len(), 2);
    assert!(keys.iter().all(|k| k.time == 0.5));
    assert_eq!(keys[0].transform, [Transform::Translate([-1.0, 0.5, 0.0])]);
}

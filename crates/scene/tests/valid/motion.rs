//! Motion: camera keys, a gradual shutter, transform and deformation keys, the `original`
//! switches of motion, and keys on a shifted or closed shutter.

use reyes_scene::{CameraKey, PointsKey, Shutter, ShutterShape, Transform, TransformKey};

use crate::{FULL, ok, reads_back};

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

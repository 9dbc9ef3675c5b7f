//! Bad-input catalogue of the distributed ray tracing fields (area lights, shadows, traced
//! reflection and refraction, the pool-ball pattern, rolling, the hider method and the
//! `raytrace` limits): each bad input yields exactly one line naming the file, the position,
//! the field path and what is wrong.
//!
//! Each case edits one spot of a valid base scene and gives the whole expected line.

mod common;

use std::path::Path;

use reyes_scene::parse;

/// A valid scene using every new field, which every case edits in one place.
const BASE: &str = r#"Scene(
  image: (width: 64, height: 48),
  camera: (eye: (0.0, 2.0, -10.0), look_at: (0.0, 1.0, 0.0), shutter: (open: 0.0, close: 1.0)),
  hider: (method: Stochastic, pixel_samples: (2, 2)),
  lights: [
    Point(from: (0.0, 5.0, 0.0), shadows: true),
    Area(shape: Sphere(center: (0.0, 8.0, 0.0), radius: 1.0), intensity: 20.0),
    Area(shape: Disk(center: (2.0, 8.0, 0.0), normal: (0.0, -1.0, 0.0), radius: 0.5)),
    Area(shape: Rectangle(corner: (-1.0, 9.0, -1.0), edge_u: (2.0, 0.0, 0.0), edge_v: (0.0, 0.0, 2.0)),
         motion: [(time: 0.0, offset: (0.0, 0.0, 0.0)), (time: 1.0, offset: (1.0, 0.0, 0.0), intensity: 0.5)]),
  ],
  objects: [
    (name: "floor", shape: Disk(radius: 10.0), transform: [Rotate(angle: 90.0, axis: (1.0, 0.0, 0.0))],
     material: Matte(color: (0.5, 0.5, 0.5))),
    (name: "mirror", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
     reflect: Some((color: (0.9, 0.9, 0.9), gloss: 5.0))),
    (name: "glass", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
     refract: Some((ior: 1.5, color: (1.0, 1.0, 1.0), blur: 2.0))),
    (name: "ball", shape: Sphere(radius: 1.0), transform: [Rotate(angle: 30.0, axis: (1.0, 0.0, 0.0))],
     material: Plastic(color: (1.0, 1.0, 1.0)),
     pattern: Some(PoolBall(color: (0.9, 0.7, 0.1), striped: true)),
     roll: Some((radius: 1.0, up: (0.0, 1.0, 0.0),
                 path: [(time: 0.0, position: (-2.0, 1.0, 0.0)), (time: 0.5, position: (0.0, 1.0, 0.0)),
                        (time: 1.0, position: (0.0, 1.0, 2.0))],
                 steps: 8))),
  ],
  raytrace: (max_depth: 4, min_weight: 0.01, vertex_rays: 1),
)
"#;

/// The file name every error must carry.
const FILE: &str = "scenes/trace.ron";

/// One bad input: each edit replaces its first text (which occurs once in [`BASE`]) by its
/// second; `shown` is the whole expected error line.
struct Case {
    name: &'static str,
    edits: &'static [(&'static str, &'static str)],
    shown: &'static str,
}

#[rustfmt::skip]
const CASES: &[Case] = &[
    // The hider method and the ray-tracing limits.
    Case { name: "ray-tracing hider with solids", edits: &[("method: Stochastic", "method: RayTrace"), ("  raytrace:", "  solids: [(tree: Union([Object(\"mirror\"), Object(\"glass\")]))],\n  raytrace:")], shown: "scenes/trace.ron:4:19: hider.method: the ray-tracing hider does not evaluate CSG solids; use method: Stochastic" },
    Case { name: "max depth 0 with reflection", edits: &[("max_depth: 4", "max_depth: 0")], shown: "scenes/trace.ron:27:25: raytrace.max_depth: must be >= 1 when an object reflects or refracts (objects[1].reflect asks for rays), got 0" },
    Case { name: "max depth 0 with refraction", edits: &[("max_depth: 4", "max_depth: 0"), (",\n     reflect: Some((color: (0.9, 0.9, 0.9), gloss: 5.0))", "")], shown: "scenes/trace.ron:26:25: raytrace.max_depth: must be >= 1 when an object reflects or refracts (objects[2].refract asks for rays), got 0" },
    Case { name: "max depth too deep", edits: &[("max_depth: 4", "max_depth: 65")], shown: "scenes/trace.ron:27:25: raytrace.max_depth: must be in 0..=64, got 65" },
    Case { name: "min weight 1", edits: &[("min_weight: 0.01", "min_weight: 1.0")], shown: "scenes/trace.ron:27:40: raytrace.min_weight: must be in [0, 1), got 1" },
    Case { name: "min weight negative", edits: &[("min_weight: 0.01", "min_weight: -0.1")], shown: "scenes/trace.ron:27:40: raytrace.min_weight: must be in [0, 1), got -0.1" },
    Case { name: "min weight NaN", edits: &[("min_weight: 0.01", "min_weight: NaN")], shown: "scenes/trace.ron:27:40: raytrace.min_weight: must be finite, got NaN" },
    Case { name: "vertex rays 0", edits: &[("vertex_rays: 1", "vertex_rays: 0")], shown: "scenes/trace.ron:27:59: raytrace.vertex_rays: must be in 1..=4096, got 0" },
    Case { name: "vertex rays too many", edits: &[("vertex_rays: 1", "vertex_rays: 5000")], shown: "scenes/trace.ron:27:59: raytrace.vertex_rays: must be in 1..=4096, got 5000" },
    Case { name: "unknown hider method", edits: &[("method: Stochastic", "method: Raytrace")], shown: "scenes/trace.ron:4:19: hider.method: unknown variant `Raytrace`, expected `Stochastic` or `RayTrace`" },
    // Lights.
    Case { name: "shadows not a bool", edits: &[("shadows: true", "shadows: 1")], shown: "scenes/trace.ron:6:43: lights[0].shadows: expected boolean" },
    Case { name: "area sphere radius 0", edits: &[("(0.0, 8.0, 0.0), radius: 1.0", "(0.0, 8.0, 0.0), radius: 0.0")], shown: "scenes/trace.ron:7:57: lights[1].shape.radius: must be > 0, got 0" },
    Case { name: "area sphere radius negative", edits: &[("(0.0, 8.0, 0.0), radius: 1.0", "(0.0, 8.0, 0.0), radius: -1.0")], shown: "scenes/trace.ron:7:57: lights[1].shape.radius: must be > 0, got -1" },
    Case { name: "area sphere centre infinite", edits: &[("center: (0.0, 8.0, 0.0)", "center: (0.0, inf, 0.0)")], shown: "scenes/trace.ron:7:38: lights[1].shape.center[1]: must be finite, got inf" },
    Case { name: "area disk normal zero", edits: &[("normal: (0.0, -1.0, 0.0)", "normal: (0.0, 0.0, 0.0)")], shown: "scenes/trace.ron:8:55: lights[2].shape.normal: must be non-zero" },
    Case { name: "area disk radius negative", edits: &[("radius: 0.5", "radius: -0.5")], shown: "scenes/trace.ron:8:81: lights[2].shape.radius: must be > 0, got -0.5" },
    Case { name: "area rectangle NaN corner", edits: &[("corner: (-1.0, 9.0, -1.0)", "corner: (-1.0, NaN, -1.0)")], shown: "scenes/trace.ron:9:42: lights[3].shape.corner[1]: must be finite, got NaN" },
    Case { name: "area rectangle edge zero", edits: &[("edge_u: (2.0, 0.0, 0.0)", "edge_u: (0.0, 0.0, 0.0)")], shown: "scenes/trace.ron:9:62: lights[3].shape.edge_u: must be non-zero" },
    Case { name: "area rectangle edges parallel", edits: &[("edge_v: (0.0, 0.0, 2.0)", "edge_v: (-4.0, 0.0, 0.0)")], shown: "scenes/trace.ron:9:87: lights[3].shape.edge_v: must not be parallel to edge_u" },
    Case { name: "area light missing shape", edits: &[("Area(shape: Sphere(center: (0.0, 8.0, 0.0), radius: 1.0), intensity", "Area(intensity")], shown: "scenes/trace.ron:7:25: lights[1].shape: missing required field `shape`" },
    Case { name: "area light negative intensity", edits: &[("intensity: 20.0", "intensity: -20.0")], shown: "scenes/trace.ron:7:74: lights[1].intensity: must be >= 0, got -20" },
    Case { name: "area light negative colour", edits: &[("intensity: 20.0", "intensity: 20.0, color: (1.0, -0.5, 1.0)")], shown: "scenes/trace.ron:7:93: lights[1].color[1]: must be >= 0, got -0.5" },
    Case { name: "area light motion with one key", edits: &[("motion: [(time: 0.0, offset: (0.0, 0.0, 0.0)), ", "motion: [")], shown: "scenes/trace.ron:10:18: lights[3].motion: motion needs at least 2 keys (or none), got 1" },
    Case { name: "area light motion key outside the shutter", edits: &[("(time: 1.0, offset: (1.0, 0.0, 0.0)", "(time: 1.5, offset: (1.0, 0.0, 0.0)")], shown: "scenes/trace.ron:10:64: lights[3].motion[1].time: motion key time 1.5 is outside the shutter [0, 1]" },
    Case { name: "area light motion keys out of order", edits: &[("(time: 1.0, offset: (1.0, 0.0, 0.0)", "(time: 0.0, offset: (1.0, 0.0, 0.0)")], shown: "scenes/trace.ron:10:64: lights[3].motion[1].time: keys must be in increasing time order, got 0 after 0" },
    Case { name: "area light motion NaN offset", edits: &[("offset: (0.0, 0.0, 0.0)", "offset: (NaN, 0.0, 0.0)")], shown: "scenes/trace.ron:10:40: lights[3].motion[0].offset[0]: must be finite, got NaN" },
    Case { name: "area light motion negative intensity", edits: &[("intensity: 0.5", "intensity: -0.5")], shown: "scenes/trace.ron:10:105: lights[3].motion[1].intensity: must be >= 0, got -0.5" },
    // Traced reflection and refraction.
    Case { name: "reflect colour above 1", edits: &[("color: (0.9, 0.9, 0.9)", "color: (1.5, 0.9, 0.9)")], shown: "scenes/trace.ron:16:29: objects[1].reflect.color[0]: must be in [0, 1], got 1.5" },
    Case { name: "reflect colour negative", edits: &[("color: (0.9, 0.9, 0.9)", "color: (0.9, -0.1, 0.9)")], shown: "scenes/trace.ron:16:34: objects[1].reflect.color[1]: must be in [0, 1], got -0.1" },
    Case { name: "negative gloss", edits: &[("gloss: 5.0", "gloss: -5.0")], shown: "scenes/trace.ron:16:52: objects[1].reflect.gloss: must be in [0, 90) degrees, got -5" },
    Case { name: "gloss 90", edits: &[("gloss: 5.0", "gloss: 90.0")], shown: "scenes/trace.ron:16:52: objects[1].reflect.gloss: must be in [0, 90) degrees, got 90" },
    Case { name: "gloss NaN", edits: &[("gloss: 5.0", "gloss: NaN")], shown: "scenes/trace.ron:16:52: objects[1].reflect.gloss: must be finite, got NaN" },
    Case { name: "reflect without a colour", edits: &[("color: (0.9, 0.9, 0.9), gloss", "gloss")], shown: "scenes/trace.ron:16:31: objects[1].reflect.color: missing required field `color`" },
    Case { name: "reflect without Some", edits: &[("reflect: Some((color: (0.9, 0.9, 0.9), gloss: 5.0))", "reflect: (color: (0.9, 0.9, 0.9), gloss: 5.0)")], shown: "scenes/trace.ron:16:15: objects[1].reflect: expected `Some(...)` or `None`" },
    Case { name: "refract ior negative", edits: &[("ior: 1.5", "ior: -1.0")], shown: "scenes/trace.ron:18:26: objects[2].refract.ior: must be > 0, got -1" },
    Case { name: "refract ior 0", edits: &[("ior: 1.5", "ior: 0.0")], shown: "scenes/trace.ron:18:26: objects[2].refract.ior: must be > 0, got 0" },
    Case { name: "refract ior infinite", edits: &[("ior: 1.5", "ior: inf")], shown: "scenes/trace.ron:18:26: objects[2].refract.ior: must be finite, got inf" },
    Case { name: "refract colour above 1", edits: &[("color: (1.0, 1.0, 1.0), blur", "color: (1.0, 1.0, 1.1), blur")], shown: "scenes/trace.ron:18:49: objects[2].refract.color[2]: must be in [0, 1], got 1.1" },
    Case { name: "negative blur", edits: &[("blur: 2.0", "blur: -2.0")], shown: "scenes/trace.ron:18:61: objects[2].refract.blur: must be in [0, 90) degrees, got -2" },
    Case { name: "blur 90", edits: &[("blur: 2.0", "blur: 90.0")], shown: "scenes/trace.ron:18:61: objects[2].refract.blur: must be in [0, 90) degrees, got 90" },
    // The pool-ball pattern.
    Case { name: "pool ball colour above 1", edits: &[("PoolBall(color: (0.9, 0.7, 0.1)", "PoolBall(color: (0.9, 1.7, 0.1)")], shown: "scenes/trace.ron:21:42: objects[3].pattern.color[1]: must be in [0, 1], got 1.7" },
    Case { name: "unknown pattern", edits: &[("PoolBall(color", "Checker(color")], shown: "scenes/trace.ron:21:20: objects[3].pattern: unknown variant `Checker`, expected `PoolBall`" },
    // Rolling.
    Case { name: "roll radius 0", edits: &[("roll: Some((radius: 1.0", "roll: Some((radius: 0.0")], shown: "scenes/trace.ron:22:26: objects[3].roll.radius: must be > 0, got 0" },
    Case { name: "roll radius NaN", edits: &[("roll: Some((radius: 1.0", "roll: Some((radius: NaN")], shown: "scenes/trace.ron:22:26: objects[3].roll.radius: must be finite, got NaN" },
    Case { name: "roll up zero", edits: &[("up: (0.0, 1.0, 0.0)", "up: (0.0, 0.0, 0.0)")], shown: "scenes/trace.ron:22:35: objects[3].roll.up: must be non-zero" },
    Case { name: "roll path with one key", edits: &[("path: [(time: 0.0, position: (-2.0, 1.0, 0.0)), (time: 0.5, position: (0.0, 1.0, 0.0)),\n                        (time: 1.0, position: (0.0, 1.0, 2.0))]", "path: [(time: 0.0, position: (-2.0, 1.0, 0.0))]")], shown: "scenes/trace.ron:23:24: objects[3].roll.path: a roll needs at least 2 path keys, got 1" },
    Case { name: "roll path empty", edits: &[("path: [(time: 0.0, position: (-2.0, 1.0, 0.0)), (time: 0.5, position: (0.0, 1.0, 0.0)),\n                        (time: 1.0, position: (0.0, 1.0, 2.0))]", "path: []")], shown: "scenes/trace.ron:23:24: objects[3].roll.path: a roll needs at least 2 path keys, got 0" },
    Case { name: "roll path key outside the shutter", edits: &[("(time: 1.0, position: (0.0, 1.0, 2.0))", "(time: 1.25, position: (0.0, 1.0, 2.0))")], shown: "scenes/trace.ron:24:32: objects[3].roll.path[2].time: motion key time 1.25 is outside the shutter [0, 1]" },
    Case { name: "roll path keys out of order", edits: &[("(time: 0.5, position: (0.0, 1.0, 0.0))", "(time: 0.0, position: (0.0, 1.0, 0.0))")], shown: "scenes/trace.ron:23:73: objects[3].roll.path[1].time: keys must be in increasing time order, got 0 after 0" },
    Case { name: "roll path NaN position", edits: &[("position: (0.0, 1.0, 2.0)", "position: (0.0, 1.0, NaN)")], shown: "scenes/trace.ron:24:58: objects[3].roll.path[2].position[2]: must be finite, got NaN" },
    Case { name: "roll path leaves the plane", edits: &[("position: (0.0, 1.0, 2.0)", "position: (0.0, 1.5, 2.0)")], shown: "scenes/trace.ron:24:47: objects[3].roll.path[2].position: the ball must roll on a plane normal to roll.up, but its centre moves 0.5 along up from path[1]" },
    Case { name: "roll steps 0", edits: &[("steps: 8", "steps: 0")], shown: "scenes/trace.ron:25:25: objects[3].roll.steps: must be in 1..=1024, got 0" },
    Case { name: "roll steps too many", edits: &[("steps: 8", "steps: 1025")], shown: "scenes/trace.ron:25:25: objects[3].roll.steps: must be in 1..=1024, got 1025" },
    Case { name: "roll steps too coarse", edits: &[("steps: 8", "steps: 1")], shown: "scenes/trace.ron:25:25: objects[3].roll.steps: the ball turns 114.59156 degrees from path[0] to path[1], more than 45 degrees per step (steps 1); steps must be at least 3" },
    Case { name: "roll segment too long for any steps", edits: &[("position: (0.0, 1.0, 2.0)", "position: (0.0, 1.0, 9000.0)")], shown: "scenes/trace.ron:25:25: objects[3].roll.steps: the ball turns 515662 degrees from path[1] to path[2], more than 45 degrees per step (steps 8); more than 1024 steps would be needed: add path keys" },
    Case { name: "roll with motion", edits: &[("pattern: Some(PoolBall", "motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Translate((1.0, 0.0, 0.0))])],\n     pattern: Some(PoolBall")], shown: "scenes/trace.ron:23:12: objects[3].roll: an object cannot have both roll and motion: roll generates the motion keys; remove one of them" },
    Case { name: "roll with a moving rest transform", edits: &[("transform: [Rotate(angle: 30.0, axis: (1.0, 0.0, 0.0))]", "transform: [Rotate(angle: 30.0, axis: (1.0, 0.0, 0.0)), Translate((0.0, 1.0, 0.0))]")], shown: "scenes/trace.ron:19:104: objects[3].transform[1]: with roll, the transform is the ball's rest orientation and must keep its centre (the object's origin) in place; roll.path places the ball" },
    Case { name: "roll with a translating matrix", edits: &[("transform: [Rotate(angle: 30.0, axis: (1.0, 0.0, 0.0))]", "transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.5), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0)))]")], shown: "scenes/trace.ron:19:60: objects[3].transform[0]: with roll, the transform is the ball's rest orientation and must keep its centre (the object's origin) in place; roll.path places the ball" },
    Case { name: "roll without a radius", edits: &[("roll: Some((radius: 1.0, ", "roll: Some((")], shown: "scenes/trace.ron:25:26: objects[3].roll.radius: missing required field `radius`" },
];

fn run(case: &Case) -> String {
    let mut text = BASE.to_string();
    for (from, to) in case.edits {
        assert_eq!(text.matches(from).count(), 1, "{}: {from:?} must occur once", case.name);
        text = text.replacen(from, to, 1);
    }
    match parse(&text, Path::new(FILE)) {
        Ok(_) => panic!("{}: the scene was accepted:\n{text}", case.name),
        Err(e) => e.to_string(),
    }
}

#[test]
fn the_base_scene_is_valid() {
    let scene = parse(BASE, Path::new(FILE)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.lights.len(), 4);
    assert_eq!(scene.objects.len(), 4);
}

#[test]
fn every_case_gives_its_exact_line() {
    let mut wrong = Vec::new();
    for case in CASES {
        let shown = run(case);
        if shown != case.shown {
            wrong.push(format!("{}\n  got      {shown}\n  expected {}", case.name, case.shown));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// A roll may not expand into more than 2^20 transforms: a long path at many steps is
/// rejected at `steps`, before anything is generated.
#[test]
fn the_size_of_a_roll_is_limited() {
    let path = |n: usize| {
        let keys: Vec<String> = (0..n)
            .map(|i| {
                let t = i as f32 / (n - 1) as f32;
                format!("(time: {t:?}, position: ({:?}, 1.0, 0.0))", i as f32 * 0.01)
            })
            .collect();
        format!("path: [{}],\n                 steps: 1024", keys.join(", "))
    };
    let from = "path: [(time: 0.0, position: (-2.0, 1.0, 0.0)), (time: 0.5, position: (0.0, 1.0, 0.0)),\n                        (time: 1.0, position: (0.0, 1.0, 2.0))],\n                 steps: 8";
    assert_eq!(BASE.matches(from).count(), 1);
    let e = parse(&BASE.replacen(from, &path(1100), 1), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some(
            "scenes/trace.ron:24:25: objects[3].roll.steps: the roll would generate 1125377 keys of up to 4 transforms each, more than 1048576 transforms in all: use fewer steps or path keys"
        )
    );
    let scene = parse(&BASE.replacen(from, &path(200), 1), Path::new(FILE))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.objects[3].motion.len(), 199 * 1024 + 1);
}

/// A bad ray-tracing value is a bad scene for `load` too: one line, exit code 2.
#[test]
fn a_bad_ior_is_exit_code_2() {
    let path =
        common::temp_file("bad-ior.ron", BASE.replacen("ior: 1.5", "ior: -1.0", 1).as_bytes());
    let shown = common::load_bad(&path).to_string();
    assert!(
        shown.ends_with("bad-ior.ron:18:26: objects[2].refract.ior: must be > 0, got -1"),
        "{shown}"
    );
}

/// The ray-tracing hider is accepted without solids; a closed shutter takes roll and light
/// keys all at `open`.
#[test]
fn variations_of_the_base_are_valid() {
    for edits in [
        &[("method: Stochastic", "method: RayTrace")][..],
        &[
            ("shutter: (open: 0.0, close: 1.0)", "shutter: (open: 0.0, close: 0.0)"),
            ("(time: 1.0, offset", "(time: 0.0, offset"),
            ("(time: 0.5, position", "(time: 0.0, position"),
            ("(time: 1.0, position", "(time: 0.0, position"),
        ][..],
    ] {
        let mut text = BASE.to_string();
        for (from, to) in edits {
            assert_eq!(text.matches(from).count(), 1, "{from}");
            text = text.replacen(from, to, 1);
        }
        if let Err(e) = parse(&text, Path::new(FILE)) {
            panic!("{e}\n{text}");
        }
    }
}

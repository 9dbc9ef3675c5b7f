//! Bad-input catalogue: every rejected scene yields one line naming the file, the field path and
//! the line:column of the offending text.
//!
//! Each case edits one spot of a valid base scene; `at` is the expected 1-based line and column.

mod common;

use std::path::Path;

use reyes_scene::{SceneError, parse};

/// A valid scene that every case edits in one place.
const BASE: &str = r#"Scene(
  image: (width: 640, height: 480),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), fov: 35.0, hither: 0.1, yon: 100.0),
  hider: (pixel_samples: (4, 4), filter: (kind: Gaussian, width: 2.0)),
  lights: [Ambient(intensity: 0.1), Distant(from: (1.0, 1.0, -1.0))],
  objects: [
    (name: "ball", shape: Sphere(radius: 1.0), material: Matte(color: (0.8, 0.1, 0.1))),
  ],
)
"#;

/// The file name every error must carry.
const FILE: &str = "scenes/bad.ron";

/// One bad input: replace `from` (which occurs once in [`BASE`]) by `to`.
struct Case {
    name: &'static str,
    from: &'static str,
    to: &'static str,
    field: &'static str,
    at: Option<(usize, usize)>,
}

#[rustfmt::skip]
const CASES: &[Case] = &[
    Case { name: "malformed: missing comma between fields", from: "480),\n  camera", to: "480)\n  camera", field: "", at: Some((3, 3)) },
    Case { name: "malformed: unclosed scene", from: "],\n)\n", to: "],\n", field: "", at: Some((8, 5)) },
    Case { name: "malformed: stray closing bracket", from: "fov: 35.0,", to: "fov: 35.0],", field: "camera", at: Some((3, 71)) },
    Case { name: "malformed: unclosed string", from: "\"ball\"", to: "\"ball", field: "objects[0].name", at: Some((7, 12)) },
    Case { name: "malformed: empty file", from: BASE, to: "", field: "", at: Some((1, 1)) },
    Case { name: "malformed: trailing text", from: "],\n)\n", to: "],\n)\nScene()\n", field: "", at: Some((10, 1)) },
    Case { name: "malformed: unclosed comment", from: "],\n)\n", to: "],\n)\n/* end\n", field: "", at: Some((10, 1)) },
    Case { name: "sphere cut without Some", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, zmin: -0.5)", field: "objects[0].shape.zmin", at: Some((7, 53)) },
    Case { name: "matrix written with brackets", from: "material:", to: "transform: [Matrix([[1.0, 0.0, 0.0, 0.0]])], material:", field: "objects[0].transform[0]", at: Some((7, 67)) },
    Case { name: "unknown field", from: "height: 480)", to: "height: 480, depth: 8)", field: "image.depth", at: Some((2, 36)) },
    Case { name: "unknown field in a shape", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, radius2: 2.0)", field: "objects[0].shape.radius2", at: Some((7, 47)) },
    Case { name: "unknown variant", from: "Gaussian", to: "Gauss", field: "hider.filter.kind", at: Some((4, 49)) },
    Case { name: "missing required field", from: "width: 640, height: 480)", to: "width: 640)", field: "image.height", at: Some((2, 21)) },
    Case { name: "missing required field in a shape", from: "Sphere(radius: 1.0)", to: "Sphere()", field: "objects[0].shape.radius", at: Some((7, 34)) },
    Case { name: "missing required section", from: "  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), fov: 35.0, hither: 0.1, yon: 100.0),\n", to: "", field: "camera", at: Some((8, 1)) },
    Case { name: "duplicate field", from: "height: 480)", to: "height: 480, width: 2)", field: "image.width", at: Some((2, 36)) },
    Case { name: "wrong type", from: "width: 640", to: "width: \"640\"", field: "image.width", at: Some((2, 18)) },
    Case { name: "negative integer", from: "width: 640", to: "width: -640", field: "image.width", at: Some((2, 19)) },
    Case { name: "wrong tuple length", from: "(0.0, 1.0, -10.0)", to: "(0.0, 1.0)", field: "camera.eye", at: Some((3, 26)) },
    Case { name: "lens without Some", from: "yon: 100.0)", to: "yon: 100.0, lens: (focal_length: 1.0, f_stop: 2.8, focal_distance: 8.0))", field: "camera.lens", at: Some((3, 104)) },
    Case { name: "width 0", from: "width: 640", to: "width: 0", field: "image.width", at: Some((2, 18)) },
    Case { name: "height 0", from: "height: 480", to: "height: 0", field: "image.height", at: Some((2, 31)) },
    Case { name: "width too large", from: "width: 640", to: "width: 70000", field: "image.width", at: Some((2, 18)) },
    Case { name: "pixel samples 0", from: "(4, 4)", to: "(4, 0)", field: "hider.pixel_samples[1]", at: Some((4, 30)) },
    Case { name: "pixel samples too many", from: "(4, 4)", to: "(65, 4)", field: "hider.pixel_samples[0]", at: Some((4, 27)) },
    Case { name: "fov 0", from: "fov: 35.0", to: "fov: 0.0", field: "camera.fov", at: Some((3, 67)) },
    Case { name: "fov 180", from: "fov: 35.0", to: "fov: 180.0", field: "camera.fov", at: Some((3, 67)) },
    Case { name: "fov 190", from: "fov: 35.0", to: "fov: 190.0", field: "camera.fov", at: Some((3, 67)) },
    Case { name: "hither 0", from: "hither: 0.1", to: "hither: 0.0", field: "camera.hither", at: Some((3, 81)) },
    Case { name: "hither negative", from: "hither: 0.1", to: "hither: -1.0", field: "camera.hither", at: Some((3, 81)) },
    Case { name: "hither equal to yon", from: "hither: 0.1, yon: 100.0", to: "hither: 100.0, yon: 100.0", field: "camera.yon", at: Some((3, 93)) },
    Case { name: "hither beyond yon", from: "hither: 0.1, yon: 100.0", to: "hither: 200.0, yon: 100.0", field: "camera.yon", at: Some((3, 93)) },
    Case { name: "eye at look_at", from: "look_at: (0.0, 0.0, 0.0)", to: "look_at: (0.0, 1.0, -10.0)", field: "camera.look_at", at: Some((3, 45)) },
    Case { name: "up parallel to view", from: "fov: 35.0", to: "up: (0.0, -0.1, 1.0), fov: 35.0", field: "camera.up", at: Some((3, 66)) },
    Case { name: "up zero", from: "fov: 35.0", to: "up: (0.0, 0.0, 0.0), fov: 35.0", field: "camera.up", at: Some((3, 66)) },
    Case { name: "shutter closes before it opens", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 1.0, close: 0.5))", field: "camera.shutter.close", at: Some((3, 126)) },
    Case { name: "lens f_stop 0", from: "yon: 100.0)", to: "yon: 100.0, lens: Some((focal_length: 1.0, f_stop: 0.0, focal_distance: 8.0)))", field: "camera.lens.f_stop", at: Some((3, 137)) },
    Case { name: "filter width 0", from: "width: 2.0", to: "width: 0.0", field: "hider.filter.width", at: Some((4, 66)) },
    Case { name: "filter width negative", from: "width: 2.0", to: "width: -2.0", field: "hider.filter.width", at: Some((4, 66)) },
    Case { name: "filter width too wide", from: "width: 2.0", to: "width: 17.0", field: "hider.filter.width", at: Some((4, 66)) },
    Case { name: "filter height 0", from: "width: 2.0)", to: "width: 2.0, height: Some(0.0))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height negative", from: "width: 2.0)", to: "width: 2.0, height: Some(-1.0))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height too tall", from: "width: 2.0)", to: "width: 2.0, height: Some(17.0))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height NaN", from: "width: 2.0)", to: "width: 2.0, height: Some(NaN))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height without Some", from: "width: 2.0)", to: "width: 2.0, height: 1.0)", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "RenderMan filter width negative", from: "kind: Gaussian, width: 2.0", to: "kind: RiGaussian, width: -2.0", field: "hider.filter.width", at: Some((4, 68)) },
    Case { name: "unknown RenderMan filter", from: "Gaussian", to: "RiLanczos", field: "hider.filter.kind", at: Some((4, 49)) },
    Case { name: "bucket size 0", from: "(4, 4),", to: "(4, 4), bucket_size: (0, 16),", field: "hider.bucket_size[0]", at: Some((4, 48)) },
    Case { name: "shading rate 0", from: "(4, 4),", to: "(4, 4), shading_rate: 0.0,", field: "hider.shading_rate", at: Some((4, 48)) },
    Case { name: "max grid size 0", from: "(4, 4),", to: "(4, 4), max_grid_size: 0,", field: "hider.max_grid_size", at: Some((4, 49)) },
    Case { name: "NaN fov", from: "fov: 35.0", to: "fov: NaN", field: "camera.fov", at: Some((3, 67)) },
    Case { name: "inf yon", from: "yon: 100.0", to: "yon: inf", field: "camera.yon", at: Some((3, 91)) },
    Case { name: "-inf eye", from: "-10.0", to: "-inf", field: "camera.eye[2]", at: Some((3, 28)) },
    Case { name: "NaN light intensity", from: "intensity: 0.1", to: "intensity: NaN", field: "lights[0].intensity", at: Some((5, 31)) },
    Case { name: "overflowing float", from: "radius: 1.0", to: "radius: 1e39", field: "objects[0].shape.radius", at: Some((7, 42)) },
    Case { name: "negative light intensity", from: "intensity: 0.1", to: "intensity: -0.1", field: "lights[0].intensity", at: Some((5, 31)) },
    Case { name: "negative light colour", from: "Ambient(intensity: 0.1)", to: "Ambient(color: (1.0, -1.0, 1.0))", field: "lights[0].color[1]", at: Some((5, 33)) },
    Case { name: "distant light from equals to", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Distant(from: (1.0, 1.0, -1.0), to: (1.0, 1.0, -1.0))", field: "lights[1].to", at: Some((5, 73)) },
    Case { name: "distant light at the default target", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Distant(from: (0.0, 0.0, 0.0))", field: "lights[1].to", at: Some((5, 37)) },
    Case { name: "negative radius", from: "radius: 1.0", to: "radius: -1.0", field: "objects[0].shape.radius", at: Some((7, 42)) },
    Case { name: "sphere zmin above radius", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, zmin: Some(2.0))", field: "objects[0].shape.zmin", at: Some((7, 53)) },
    Case { name: "sphere zmax at zmin", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, zmin: Some(0.5), zmax: Some(0.5))", field: "objects[0].shape.zmax", at: Some((7, 70)) },
    Case { name: "sphere thetamax 0", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, thetamax: 0.0)", field: "objects[0].shape.thetamax", at: Some((7, 57)) },
    Case { name: "sphere thetamax above 360", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, thetamax: 361.0)", field: "objects[0].shape.thetamax", at: Some((7, 57)) },
    Case { name: "cylinder zmax at zmin", from: "Sphere(radius: 1.0)", to: "Cylinder(radius: 1.0, zmin: 1.0, zmax: 1.0)", field: "objects[0].shape.zmax", at: Some((7, 66)) },
    Case { name: "cone height 0", from: "Sphere(radius: 1.0)", to: "Cone(height: 0.0, radius: 1.0)", field: "objects[0].shape.height", at: Some((7, 40)) },
    Case { name: "disk radius 0", from: "Sphere(radius: 1.0)", to: "Disk(radius: 0.0)", field: "objects[0].shape.radius", at: Some((7, 40)) },
    Case { name: "torus minor radius negative", from: "Sphere(radius: 1.0)", to: "Torus(major_radius: 1.0, minor_radius: -0.25)", field: "objects[0].shape.minor_radius", at: Some((7, 66)) },
    Case { name: "torus phimax below phimin", from: "Sphere(radius: 1.0)", to: "Torus(major_radius: 1.0, minor_radius: 0.25, phimin: 90.0, phimax: 45.0)", field: "objects[0].shape.phimax", at: Some((7, 94)) },
    Case { name: "torus tube sweep above 360", from: "Sphere(radius: 1.0)", to: "Torus(major_radius: 1.0, minor_radius: 0.25, phimin: -90.0, phimax: 290.0)", field: "objects[0].shape.phimax", at: Some((7, 95)) },
    Case { name: "mesh without faces", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0)], faces: [])", field: "objects[0].shape.faces", at: Some((7, 66)) },
    Case { name: "mesh index out of range", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 3]])", field: "objects[0].shape.faces[0][2]", at: Some((7, 108)) },
    Case { name: "mesh face with 5 indices", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2], [0, 1, 2, 0, 1]])", field: "objects[0].shape.faces[1]", at: Some((7, 112)) },
    Case { name: "mesh face with 2 indices", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1]])", field: "objects[0].shape.faces[0]", at: Some((7, 101)) },
    Case { name: "mesh colours length mismatch", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]], colors: Some([(1.0, 1.0, 1.0)]))", field: "objects[0].shape.colors", at: Some((7, 121)) },
    Case { name: "mesh NaN point", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, NaN, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]])", field: "objects[0].shape.points[1][1]", at: Some((7, 64)) },
    Case { name: "rotate about a zero axis", from: "material:", to: "transform: [Rotate(angle: 30.0, axis: (0.0, 0.0, 0.0))], material:", field: "objects[0].transform[0].axis", at: Some((7, 86)) },
    Case { name: "scale by zero", from: "material:", to: "transform: [Translate((1.0, 0.0, 0.0)), Scale((2.0, 0.0, 2.0))], material:", field: "objects[0].transform[1][1]", at: Some((7, 100)) },
    Case { name: "projective matrix", from: "material:", to: "transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 1.0, 1.0)))], material:", field: "objects[0].transform[0][3]", at: Some((7, 134)) },
    Case { name: "singular matrix", from: "material:", to: "transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0)))], material:", field: "objects[0].transform[0]", at: Some((7, 60)) },
    Case { name: "material colour above 1", from: "(0.8, 0.1, 0.1)", to: "(0.8, 1.5, 0.1)", field: "objects[0].material.color[1]", at: Some((7, 77)) },
    Case { name: "material opacity negative", from: "(0.8, 0.1, 0.1))", to: "(0.8, 0.1, 0.1), opacity: (1.0, 1.0, -0.5))", field: "objects[0].material.opacity[2]", at: Some((7, 108)) },
    Case { name: "plastic roughness 0", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Plastic(color: (0.8, 0.1, 0.1), roughness: 0.0)", field: "objects[0].material.roughness", at: Some((7, 101)) },
    Case { name: "negative kd", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Matte(color: (0.8, 0.1, 0.1), kd: -1.0)", field: "objects[0].material.kd", at: Some((7, 92)) },
    Case { name: "gradual shutter ramp 0", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.0, close: 1.0, shape: Gradual(ramp: 0.0)))", field: "camera.shutter.shape.ramp", at: Some((3, 152)) },
    Case { name: "gradual shutter ramp above 0.5", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.0, close: 1.0, shape: Gradual(ramp: 0.6)))", field: "camera.shutter.shape.ramp", at: Some((3, 152)) },
    Case { name: "gradual shutter ramp negative", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.0, close: 1.0, shape: Gradual(ramp: -0.25)))", field: "camera.shutter.shape.ramp", at: Some((3, 152)) },
    Case { name: "gradual shutter ramp NaN", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.0, close: 1.0, shape: Gradual(ramp: NaN)))", field: "camera.shutter.shape.ramp", at: Some((3, 152)) },
    Case { name: "gradual shutter without ramp", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.0, close: 1.0, shape: Gradual()))", field: "camera.shutter.shape.ramp", at: Some((3, 146)) },
    Case { name: "unknown shutter shape", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.0, close: 1.0, shape: Box))", field: "camera.shutter.shape", at: Some((3, 138)) },
    Case { name: "camera motion with one key", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion", at: Some((3, 106)) },
    Case { name: "camera motion key after shutter close", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 1.5, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[1].time", at: Some((3, 177)) },
    Case { name: "camera motion key before shutter open", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: -0.5, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 1.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[0].time", at: Some((3, 114)) },
    Case { name: "camera motion keys out of order", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 0.7, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 0.5, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[2].time", at: Some((3, 240)) },
    Case { name: "camera motion keys at the same time", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.5, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 0.5, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[1].time", at: Some((3, 177)) },
    Case { name: "camera motion NaN time", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: NaN, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 1.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[0].time", at: Some((3, 114)) },
    Case { name: "camera motion inf eye", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 1.0, eye: (inf, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[1].eye[0]", at: Some((3, 188)) },
    Case { name: "camera motion NaN up", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), up: (0.0, NaN, 0.0)), (time: 1.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[0].up[1]", at: Some((3, 179)) },
    Case { name: "camera motion key eye at look_at", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 1.0, eye: (2.0, 0.0, 0.0), look_at: (2.0, 0.0, 0.0))])", field: "camera.motion[1].look_at", at: Some((3, 213)) },
    Case { name: "camera motion key up zero", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 0.0, 0.0)), (time: 1.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[0].up", at: Some((3, 173)) },
    Case { name: "camera motion key up parallel to view", from: "yon: 100.0)", to: "yon: 100.0, motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 1.0, eye: (0.0, 5.0, 0.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[1].up", at: Some((3, 170)) },
    Case { name: "transform motion with one key", from: "material:", to: "motion: [(time: 0.0, transform: [Translate((1.0, 0.0, 0.0))])], material:", field: "objects[0].motion", at: Some((7, 56)) },
    Case { name: "transform motion key outside the shutter", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.5, transform: [Translate((1.0, 0.0, 0.0))])], material:", field: "objects[0].motion[1].time", at: Some((7, 92)) },
    Case { name: "transform motion keys out of order", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 0.7, transform: []), (time: 0.5, transform: [])], material:", field: "objects[0].motion[2].time", at: Some((7, 120)) },
    Case { name: "transform motion inf time", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: inf, transform: [])], material:", field: "objects[0].motion[1].time", at: Some((7, 92)) },
    Case { name: "transform motion NaN translate", from: "material:", to: "motion: [(time: 0.0, transform: [Translate((0.0, NaN, 0.0))]), (time: 1.0, transform: [])], material:", field: "objects[0].motion[0].transform[0][1]", at: Some((7, 97)) },
    Case { name: "transform motion rotate about a zero axis", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Rotate(angle: 90.0, axis: (0.0, 0.0, 0.0))])], material:", field: "objects[0].motion[1].transform[0].axis", at: Some((7, 135)) },
    Case { name: "transform motion scale by zero", from: "material:", to: "motion: [(time: 0.0, transform: [Translate((1.0, 0.0, 0.0)), Scale((1.0, 1.0, 0.0))]), (time: 1.0, transform: [])], material:", field: "objects[0].motion[0].transform[1][2]", at: Some((7, 126)) },
    Case { name: "transform motion projective matrix", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.5, 0.0, 0.0, 1.0)))])], material:", field: "objects[0].motion[1].transform[0][3]", at: Some((7, 183)) },
    Case { name: "transform motion singular matrix", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)))])], material:", field: "objects[0].motion[1].transform[0]", at: Some((7, 109)) },
    Case { name: "closed shutter with a key after open", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.5, close: 0.5), motion: [(time: 0.5, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 0.6, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[1].time", at: Some((3, 211)) },
    Case { name: "key before a shifted shutter", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 1.0, close: 2.0), motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 2.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[0].time", at: Some((3, 148)) },
    Case { name: "deformation of a sphere", from: "material:", to: "deform: [(time: 0.0, points: []), (time: 1.0, points: [])], material:", field: "objects[0].deform", at: Some((7, 56)) },
    Case { name: "deformation with one key", from: "Sphere(radius: 1.0)", to: "BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)])]", field: "objects[0].deform", at: Some((7, 128)) },
    Case { name: "deformation of a patch with 3 points", from: "0.1))),\n", to: "0.1))),\n    (shape: BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), material: Matte(color: (0.5, 0.5, 0.5)),\n     deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]),\n              (time: 1.0, points: [(0.0, 0.0, 1.0), (1.0, 0.0, 1.0), (0.0, 1.0, 1.0)])]),\n", field: "objects[1].deform[1].points", at: Some((10, 35)) },
    Case { name: "deformation of a mesh with too many points", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]), (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[0].points", at: Some((7, 143)) },
    Case { name: "deformation key outside the shutter", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]), (time: 2.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[1].time", at: Some((7, 204)) },
    Case { name: "deformation keys out of order", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]), (time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[1].time", at: Some((7, 204)) },
    Case { name: "deformation NaN point", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]), (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (NaN, 1.0, 0.0)])]", field: "objects[0].deform[1].points[2][0]", at: Some((7, 253)) },
    Case { name: "deformation points written as a tuple", from: "Sphere(radius: 1.0)", to: "BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), deform: [(time: 0.0, points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), (time: 1.0, points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)))]", field: "objects[0].deform[0].points", at: Some((7, 149)) },
    Case { name: "solid with a bare object", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(name: \"lonely\", tree: Object(\"ball\"))],\n)", field: "solids[0].tree", at: Some((10, 35)) },
    Case { name: "union with one operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\")]))],\n)", field: "solids[0].tree", at: Some((11, 19)) },
    Case { name: "empty intersection", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Intersection([]))],\n)", field: "solids[0].tree", at: Some((11, 19)) },
    Case { name: "nested union with one operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Union([Object(\"ball\")]), Object(\"hole\")))],\n)", field: "solids[0].tree[0]", at: Some((11, 30)) },
    Case { name: "unknown operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"hoel\")))],\n)", field: "solids[0].tree[1]", at: Some((11, 46)) },
    Case { name: "ambiguous operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"ball\", shape: Sphere(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"hole\"), Object(\"ball\")]))],\n)", field: "solids[0].tree[1]", at: Some((11, 42)) },
    Case { name: "unnamed operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (shape: Sphere(radius: 3.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"\")))],\n)", field: "solids[0].tree[1]", at: Some((11, 46)) },
    Case { name: "object used twice in one solid", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"hole\"), Object(\"ball\")]))],\n)", field: "solids[0].tree[2]", at: Some((11, 58)) },
    Case { name: "object used by two solids", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"cap\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"hole\"))), (tree: Intersection([Object(\"cap\"), Object(\"ball\")]))],\n)", field: "solids[1].tree[1]", at: Some((11, 100)) },
    Case { name: "disk operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"plate\")))],\n)", field: "solids[0].tree[1]", at: Some((11, 46)) },
    Case { name: "bilinear patch operand", from: "  ],\n)", to: "    (name: \"sheet\", shape: BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"sheet\"), Object(\"ball\")]))],\n)", field: "solids[0].tree[0]", at: Some((10, 26)) },
    Case { name: "sphere cut at zmax operand", from: "  ],\n)", to: "    (name: \"dome\", shape: Sphere(radius: 1.0, zmax: Some(0.5)), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Intersection([Object(\"ball\"), Object(\"dome\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 49)) },
    Case { name: "sphere cut at zmin operand", from: "  ],\n)", to: "    (name: \"dome\", shape: Sphere(radius: 1.0, zmin: Some(-0.5), zmax: Some(2.0)), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Intersection([Object(\"ball\"), Object(\"dome\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 49)) },
    Case { name: "partial sphere operand", from: "  ],\n)", to: "    (name: \"wedge\", shape: Sphere(radius: 2.0, thetamax: 270.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"wedge\"), Object(\"ball\")))],\n)", field: "solids[0].tree[0]", at: Some((10, 30)) },
    Case { name: "partial cylinder operand", from: "  ],\n)", to: "    (name: \"trough\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0, thetamax: 180.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"trough\")))],\n)", field: "solids[0].tree[1]", at: Some((10, 46)) },
    Case { name: "partial cone operand", from: "  ],\n)", to: "    (name: \"fan\", shape: Cone(height: 2.0, radius: 0.5, thetamax: 90.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"fan\")))],\n)", field: "solids[0].tree[1]", at: Some((10, 46)) },
    Case { name: "torus with a partial tube", from: "  ],\n)", to: "    (name: \"arch\", shape: Torus(major_radius: 1.0, minor_radius: 0.25, phimax: 180.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"arch\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "torus with a partial sweep", from: "  ],\n)", to: "    (name: \"arch\", shape: Torus(major_radius: 1.0, minor_radius: 0.25, phimin: -90.0, phimax: 270.0, thetamax: 90.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"arch\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "open mesh operand", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 1], [0, 1, 3], [0, 3, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "mesh edge shared by three faces", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 1, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "inconsistently oriented mesh", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "mesh face through a point twice", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 0, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "mesh of degenerate faces", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 0, 1], [2, 2, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "open operand deep in a tree", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"cap\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Union([Object(\"ball\"), Intersection([Object(\"hole\"), Object(\"plate\")])]), Object(\"cap\")))],\n)", field: "solids[0].tree[0][1][1]", at: Some((12, 83)) },
    Case { name: "glass above 1", from: "material:", to: "glass: Some(1.5), material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "glass negative", from: "material:", to: "glass: Some(-0.25), material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "glass NaN", from: "material:", to: "glass: Some(NaN), material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "glass without Some", from: "material:", to: "glass: 0.5, material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "unknown interpolation", from: "material:", to: "interpolation: Phong, material:", field: "objects[0].interpolation", at: Some((7, 63)) },
    Case { name: "difference with one operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\")))],\n)", field: "solids[0].tree", at: Some((11, 44)) },
    Case { name: "unknown CSG operator", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Xor([Object(\"ball\"), Object(\"hole\")]))],\n)", field: "solids[0].tree", at: Some((11, 19)) },
    Case { name: "union without a list", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union(Object(\"ball\"), Object(\"hole\")))],\n)", field: "solids[0].tree[0]", at: Some((11, 25)) },
    Case { name: "operand name without quotes", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(ball), Object(\"hole\")))],\n)", field: "solids[0].tree[0]", at: Some((11, 37)) },
    Case { name: "solid without a tree", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(name: \"nothing\")],\n)", field: "solids[0].tree", at: Some((10, 28)) },
    Case { name: "unknown field in a solid", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"hole\")), op: 3)],\n)", field: "solids[0].op", at: Some((10, 63)) },
    Case { name: "hyperboloid with equal points", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (1.0, 0.0, 0.0), point2: (1.0, 0.0, 0.0))", field: "objects[0].shape.point2", at: Some((7, 72)) },
    Case { name: "hyperboloid on the z axis", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (0.0, 0.0, -1.0), point2: (0.0, 0.0, 1.0))", field: "objects[0].shape.point2", at: Some((7, 73)) },
    Case { name: "hyperboloid thetamax 0", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (1.0, 0.0, -1.0), point2: (1.0, 0.0, 1.0), thetamax: 0.0)", field: "objects[0].shape.thetamax", at: Some((7, 100)) },
    Case { name: "hyperboloid NaN point", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (1.0, NaN, -1.0), point2: (1.0, 0.0, 1.0))", field: "objects[0].shape.point1[1]", at: Some((7, 53)) },
    Case { name: "bicubic patch mesh with 5 points along u", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 5, nv: 4, points: [])", field: "objects[0].shape.nu", at: Some((7, 56)) },
    Case { name: "periodic bezier mesh with 4 points along u", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, uwrap: Periodic, points: [])", field: "objects[0].shape.nu", at: Some((7, 56)) },
    Case { name: "periodic b-spline mesh with no points along v", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 0, vwrap: Periodic, vbasis: BSpline, points: [])", field: "objects[0].shape.nv", at: Some((7, 63)) },
    Case { name: "b-spline mesh whose step leaves points over", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 9, nv: 4, ubasis: BSpline, ustep: Some(2), points: [])", field: "objects[0].shape.nu", at: Some((7, 56)) },
    Case { name: "bilinear patch mesh with 1 point along v", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bilinear, nu: 2, nv: 1, points: [])", field: "objects[0].shape.nv", at: Some((7, 64)) },
    Case { name: "patch mesh step 0", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, ustep: Some(0), points: [])", field: "objects[0].shape.ustep", at: Some((7, 73)) },
    Case { name: "matrix basis without a step", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, vbasis: Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))), points: [])", field: "objects[0].shape.vstep", at: Some((7, 27)) },
    Case { name: "NaN in a basis matrix", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, ubasis: Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, NaN, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))), ustep: Some(1), points: [])", field: "objects[0].shape.ubasis[1][2]", at: Some((7, 115)) },
    Case { name: "patch mesh with too few points", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bilinear, nu: 2, nv: 2, points: [(0.0, 0.0, 0.0)])", field: "objects[0].shape.points", at: Some((7, 75)) },
    Case { name: "patch mesh inf point", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bilinear, nu: 2, nv: 2, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, inf)])", field: "objects[0].shape.points[3][2]", at: Some((7, 138)) },
    Case { name: "nurbs order 1", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 1, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.uorder", at: Some((7, 50)) },
    Case { name: "nurbs order above 16", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 17, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.vorder", at: Some((7, 119)) },
    Case { name: "nurbs with fewer points than its order", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 3, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.nu", at: Some((7, 39)) },
    Case { name: "nurbs with a knot too few", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.uknot", at: Some((7, 60)) },
    Case { name: "nurbs knots decreasing", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 0.5], umin: 0.0, umax: 0.5, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.uknot[3]", at: Some((7, 76)) },
    Case { name: "nurbs NaN knot", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, NaN, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.vknot[1]", at: Some((7, 135)) },
    Case { name: "nurbs umin before the valid range", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: -0.5, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.umin", at: Some((7, 88)) },
    Case { name: "nurbs vmax after the valid range", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 2.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.vmax", at: Some((7, 168)) },
    Case { name: "nurbs umax at umin", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.5, umax: 0.5, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.umax", at: Some((7, 99)) },
    Case { name: "nurbs weight 0", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 0.0)])", field: "objects[0].shape.points[3][3]", at: Some((7, 264)) },
    Case { name: "nurbs with too many points", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0), (2.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.points", at: Some((7, 181)) },
    Case { name: "deformation of a nurbs with 3 points", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]), (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[1].points", at: Some((7, 392)) },
    Case { name: "hyperboloid operand", from: "  ],\n)", to: "    (name: \"hyp\", shape: Hyperboloid(point1: (1.0, 0.0, -1.0), point2: (1.0, 0.0, 1.0)), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"hyp\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "wrapped patch mesh operand", from: "  ],\n)", to: "    (name: \"tube\", shape: PatchMesh(kind: Bilinear, nu: 3, nv: 2, uwrap: Periodic, points: [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), (1.0, 0.0, 1.0), (0.0, 1.0, 1.0), (-1.0, 0.0, 1.0)]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tube\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "nurbs operand", from: "  ],\n)", to: "    (name: \"sheet\", shape: NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"sheet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "screen window right not above left", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, -2.0, -1.0, 1.0))", field: "camera.screen_window[1]", at: Some((3, 100)) },
    Case { name: "screen window top equal to bottom", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, 1.0, 1.0, 1.0))", field: "camera.screen_window[3]", at: Some((3, 110)) },
    Case { name: "screen window NaN", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((NaN, 1.0, -1.0, 1.0))", field: "camera.screen_window[0]", at: Some((3, 94)) },
    Case { name: "screen window inf", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, inf, -1.0, 1.0))", field: "camera.screen_window[1]", at: Some((3, 100)) },
    Case { name: "screen window with 3 values", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, 1.0, -1.0))", field: "camera.screen_window", at: Some((3, 109)) },
    Case { name: "screen window without Some", from: "fov: 35.0", to: "fov: 35.0, screen_window: (-1.0, 1.0, -1.0, 1.0)", field: "camera.screen_window", at: Some((3, 88)) },
    Case { name: "unknown projection", from: "fov: 35.0", to: "projection: Fisheye, fov: 35.0", field: "camera.projection", at: Some((3, 74)) },
    Case { name: "object shading rate 0", from: "material:", to: "shading_rate: Some(0.0), material:", field: "objects[0].shading_rate", at: Some((7, 62)) },
    Case { name: "object shading rate negative", from: "material:", to: "shading_rate: Some(-0.5), material:", field: "objects[0].shading_rate", at: Some((7, 62)) },
    Case { name: "object shading rate NaN", from: "material:", to: "shading_rate: Some(NaN), material:", field: "objects[0].shading_rate", at: Some((7, 62)) },
    Case { name: "light set index out of range", from: "material:", to: "lights: Some([0, 2]), material:", field: "objects[0].lights[1]", at: Some((7, 65)) },
    Case { name: "light set with a light twice", from: "material:", to: "lights: Some([1, 0, 1]), material:", field: "objects[0].lights[2]", at: Some((7, 68)) },
    Case { name: "light set without Some", from: "material:", to: "lights: [0], material:", field: "objects[0].lights", at: Some((7, 56)) },
    Case { name: "spot at its target", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (1.0, 1.0, -1.0))", field: "lights[1].to", at: Some((5, 70)) },
    Case { name: "spot without to", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0))", field: "lights[1].to", at: Some((5, 64)) },
    Case { name: "spot NaN to", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, NaN, 0.0))", field: "lights[1].to[1]", at: Some((5, 76)) },
    Case { name: "spot negative intensity", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), intensity: -2.0)", field: "lights[1].intensity", at: Some((5, 98)) },
    Case { name: "spot cone angle 0", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_angle: 0.0)", field: "lights[1].cone_angle", at: Some((5, 99)) },
    Case { name: "spot cone angle above 180", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_angle: 190.0)", field: "lights[1].cone_angle", at: Some((5, 99)) },
    Case { name: "spot cone delta negative", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_delta: -1.0)", field: "lights[1].cone_delta", at: Some((5, 99)) },
    Case { name: "spot cone delta above the cone angle", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_angle: 10.0, cone_delta: 12.0)", field: "lights[1].cone_delta", at: Some((5, 117)) },
    Case { name: "spot beam distribution negative", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), beam_distribution: -1.0)", field: "lights[1].beam_distribution", at: Some((5, 106)) },
    Case { name: "metal without colour", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(roughness: 0.2)", field: "objects[0].material.color", at: Some((7, 78)) },
    Case { name: "metal roughness 0", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 0.1, 0.1), roughness: 0.0)", field: "objects[0].material.roughness", at: Some((7, 99)) },
    Case { name: "metal colour above 1", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 1.5, 0.1))", field: "objects[0].material.color[1]", at: Some((7, 77)) },
    Case { name: "metal ks negative", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 0.1, 0.1), ks: -0.5)", field: "objects[0].material.ks", at: Some((7, 92)) },
    Case { name: "metal with kd", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 0.1, 0.1), kd: 0.5)", field: "objects[0].material.kd", at: Some((7, 88)) },
];

/// The text of `case` and the error it must produce.
fn run(case: &Case) -> SceneError {
    assert_eq!(BASE.matches(case.from).count(), 1, "{}: `from` must occur once", case.name);
    let text = BASE.replacen(case.from, case.to, 1);
    match parse(&text, Path::new(FILE)) {
        Ok(_) => panic!("{}: the scene was accepted:\n{text}", case.name),
        Err(e) => e,
    }
}

/// The case named `name`.
fn case(name: &str) -> &'static Case {
    CASES.iter().find(|c| c.name == name).unwrap_or_else(|| panic!("no case {name}"))
}

/// The one-line message of the error of the case named `name`.
fn shown(name: &str) -> String {
    run(case(name)).to_string()
}

#[test]
fn the_base_scene_is_valid() {
    let scene = parse(BASE, Path::new(FILE)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.objects.len(), 1);
}

#[test]
fn every_error_is_one_line_with_file_field_and_position() {
    for case in CASES {
        let e = run(case);
        let shown = e.to_string();
        assert!(!shown.contains('\n') && !shown.contains('\r'), "{}: {shown:?}", case.name);
        assert!(shown.starts_with(&format!("{FILE}:")), "{}: {shown}", case.name);
        assert_eq!(e.file, Path::new(FILE), "{}", case.name);
        assert_eq!(e.field, case.field, "{}: {shown}", case.name);
        assert_eq!(e.line.zip(e.col), case.at, "{}: {shown}", case.name);
        assert!(!e.message.is_empty(), "{}", case.name);
        let (line, col) = case.at.unwrap_or_default();
        let expected = if case.field.is_empty() {
            format!("{FILE}:{line}:{col}: {}", e.message)
        } else {
            format!("{FILE}:{line}:{col}: {}: {}", case.field, e.message)
        };
        assert_eq!(shown, expected, "{}", case.name);
    }
}

#[test]
fn catalogue_snapshot() {
    let shown: Vec<String> =
        CASES.iter().map(|case| format!("{}\n  {}", case.name, run(case))).collect();
    insta::assert_snapshot!("catalogue", shown.join("\n"));
}

#[test]
fn the_catalogue_covers_the_required_inputs() {
    for required in [
        "malformed: missing comma between fields",
        "unknown field",
        "missing required field",
        "width 0",
        "height 0",
        "pixel samples 0",
        "fov 0",
        "fov 180",
        "fov 190",
        "hither 0",
        "hither negative",
        "hither equal to yon",
        "filter width 0",
        "filter width negative",
        "filter height 0",
        "filter height negative",
        "filter height NaN",
        "negative radius",
        "NaN fov",
        "inf yon",
        "mesh index out of range",
        "mesh face with 5 indices",
        "mesh colours length mismatch",
        "gradual shutter ramp 0",
        "gradual shutter ramp above 0.5",
        "camera motion with one key",
        "camera motion key after shutter close",
        "camera motion keys out of order",
        "camera motion key eye at look_at",
        "camera motion key up zero",
        "camera motion key up parallel to view",
        "transform motion with one key",
        "transform motion key outside the shutter",
        "transform motion keys out of order",
        "transform motion rotate about a zero axis",
        "transform motion scale by zero",
        "transform motion singular matrix",
        "transform motion projective matrix",
        "closed shutter with a key after open",
        "deformation of a sphere",
        "deformation with one key",
        "deformation of a patch with 3 points",
        "deformation of a mesh with too many points",
        "deformation key outside the shutter",
        "deformation keys out of order",
        "deformation NaN point",
        "solid with a bare object",
        "union with one operand",
        "empty intersection",
        "unknown operand",
        "ambiguous operand",
        "object used twice in one solid",
        "object used by two solids",
        "disk operand",
        "bilinear patch operand",
        "sphere cut at zmax operand",
        "partial sphere operand",
        "partial cylinder operand",
        "partial cone operand",
        "torus with a partial tube",
        "torus with a partial sweep",
        "open mesh operand",
        "mesh edge shared by three faces",
        "inconsistently oriented mesh",
        "open operand deep in a tree",
        "glass above 1",
        "glass negative",
        "glass NaN",
        "screen window right not above left",
        "screen window top equal to bottom",
        "screen window NaN",
        "screen window inf",
        "screen window with 3 values",
        "screen window without Some",
        "unknown projection",
        "object shading rate 0",
        "object shading rate negative",
        "object shading rate NaN",
        "light set index out of range",
        "light set with a light twice",
        "light set without Some",
        "spot at its target",
        "spot without to",
        "spot NaN to",
        "spot negative intensity",
        "spot cone angle 0",
        "spot cone angle above 180",
        "spot cone delta negative",
        "spot cone delta above the cone angle",
        "spot beam distribution negative",
        "metal without colour",
        "metal roughness 0",
        "metal colour above 1",
        "metal ks negative",
        "metal with kd",
    ] {
        assert!(CASES.iter().any(|c| c.name == required), "missing case {required}");
    }
}

/// The exact text of a few errors, independent of the snapshot.
#[test]
fn exact_messages() {
    assert_eq!(
        shown("filter height negative"),
        "scenes/bad.ron:4:79: hider.filter.height: must be in (0, 16] pixels, got -1"
    );
    assert_eq!(
        shown("filter height NaN"),
        "scenes/bad.ron:4:79: hider.filter.height: must be finite, got NaN"
    );
    assert_eq!(
        shown("negative radius"),
        "scenes/bad.ron:7:42: objects[0].shape.radius: must be > 0, got -1"
    );
    assert_eq!(shown("width 0"), "scenes/bad.ron:2:18: image.width: must be in 1..=65536, got 0");
    assert_eq!(
        shown("fov 180"),
        "scenes/bad.ron:3:67: camera.fov: must be in (0, 180) degrees, got 180"
    );
    assert_eq!(shown("NaN fov"), "scenes/bad.ron:3:67: camera.fov: must be finite, got NaN");
    assert_eq!(shown("inf yon"), "scenes/bad.ron:3:91: camera.yon: must be finite, got inf");
    assert_eq!(
        shown("hither equal to yon"),
        "scenes/bad.ron:3:93: camera.yon: must be > hither (100), got 100"
    );
    assert_eq!(
        shown("pixel samples 0"),
        "scenes/bad.ron:4:30: hider.pixel_samples[1]: must be in 1..=64, got 0"
    );
    assert_eq!(
        shown("mesh index out of range"),
        "scenes/bad.ron:7:108: objects[0].shape.faces[0][2]: index 3 is out of range: the mesh has 3 points"
    );
    assert_eq!(
        shown("unknown field"),
        "scenes/bad.ron:2:36: image.depth: unknown field `depth`, expected `width` or `height`"
    );
    assert_eq!(
        shown("missing required field"),
        "scenes/bad.ron:2:21: image.height: missing required field `height`"
    );
    assert_eq!(
        shown("gradual shutter ramp above 0.5"),
        "scenes/bad.ron:3:152: camera.shutter.shape.ramp: must be in (0, 0.5], got 0.6"
    );
    assert_eq!(
        shown("camera motion key after shutter close"),
        "scenes/bad.ron:3:177: camera.motion[1].time: motion key time 1.5 is outside the shutter [0, 1]"
    );
    assert_eq!(
        shown("camera motion key up zero"),
        "scenes/bad.ron:3:173: camera.motion[0].up: must be non-zero"
    );
    assert_eq!(
        shown("transform motion with one key"),
        "scenes/bad.ron:7:56: objects[0].motion: motion needs at least 2 keys (or none), got 1"
    );
    assert_eq!(
        shown("transform motion keys out of order"),
        "scenes/bad.ron:7:120: objects[0].motion[2].time: keys must be in increasing time order, got 0.5 after 0.7"
    );
    assert_eq!(
        shown("transform motion rotate about a zero axis"),
        "scenes/bad.ron:7:135: objects[0].motion[1].transform[0].axis: must be non-zero"
    );
    assert_eq!(
        shown("closed shutter with a key after open"),
        "scenes/bad.ron:3:211: camera.motion[1].time: motion key time 0.6 is outside the shutter [0.5, 0.5]"
    );
    assert_eq!(
        shown("deformation of a sphere"),
        "scenes/bad.ron:7:56: objects[0].deform: deformation keys need a Mesh, BilinearPatch, PatchMesh or NuPatch shape, got Sphere"
    );
    assert_eq!(
        shown("deformation of a patch with 3 points"),
        "scenes/bad.ron:10:35: objects[1].deform[1].points: expected 4 points, got 3"
    );
    assert_eq!(
        shown("solid with a bare object"),
        "scenes/bad.ron:10:35: solids[0].tree: a solid needs an operator: Union, Intersection or Difference"
    );
    assert_eq!(
        shown("union with one operand"),
        "scenes/bad.ron:11:19: solids[0].tree: Union needs at least 2 operands, got 1"
    );
    assert_eq!(
        shown("empty intersection"),
        "scenes/bad.ron:11:19: solids[0].tree: Intersection needs at least 2 operands, got 0"
    );
    assert_eq!(
        shown("unknown operand"),
        "scenes/bad.ron:11:46: solids[0].tree[1]: no object is named \"hoel\""
    );
    assert_eq!(
        shown("ambiguous operand"),
        "scenes/bad.ron:11:42: solids[0].tree[1]: object name \"ball\" is ambiguous: objects[0] and objects[2] are both named \"ball\""
    );
    assert_eq!(
        shown("object used by two solids"),
        "scenes/bad.ron:11:100: solids[1].tree[1]: object \"ball\" is already used by solids[0] (at solids[0].tree[0])"
    );
    assert_eq!(
        shown("disk operand"),
        "scenes/bad.ron:11:46: solids[0].tree[1]: object \"plate\" is not closed (Disk); CSG operands must be closed solids"
    );
    assert_eq!(
        shown("open operand deep in a tree"),
        "scenes/bad.ron:12:83: solids[0].tree[0][1][1]: object \"plate\" is not closed (Disk); CSG operands must be closed solids"
    );
    assert_eq!(
        shown("open mesh operand"),
        "scenes/bad.ron:10:42: solids[0].tree[1]: object \"tet\" is not closed (Mesh: edge (2, 1) of faces[0] belongs to no other face); CSG operands must be closed solids"
    );
    assert_eq!(
        shown("inconsistently oriented mesh"),
        "scenes/bad.ron:10:42: solids[0].tree[1]: object \"tet\" is not consistently oriented (Mesh: faces[0] and faces[3] both run along edge (2, 1) from point 2 to point 1); the two faces at every edge of a closed mesh must run along it in opposite directions"
    );
    assert_eq!(
        shown("glass above 1"),
        "scenes/bad.ron:7:55: objects[0].glass: must be in [0, 1], got 1.5"
    );
}

/// A scene with `solids` made of `count` copies of `solid`, after the base scene's objects.
fn with_solids(solid: &str, count: usize) -> String {
    let list = vec![solid; count].join(",\n    ");
    BASE.replacen("  ],\n)", &format!("  ],\n  solids: [\n    {list}\n  ],\n)"), 1)
}

/// At most 65535 solids: one more is rejected at `solids`, before any solid is looked at.
#[test]
fn the_number_of_solids_is_limited() {
    let e = parse(&with_solids("(tree: Union([]))", 65536), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some("scenes/bad.ron:9:11: solids: at most 65535 solids are allowed, got 65536")
    );
    // At the limit the count passes and the first solid is checked.
    let e = parse(&with_solids("(tree: Union([]))", 65535), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some("scenes/bad.ron:10:12: solids[0].tree: Union needs at least 2 operands, got 0")
    );
}

/// At most 32768 leaves in one solid (2 * 32768 - 2 slot ids fit the renderer's `u16`),
/// counted before any leaf is resolved.
#[test]
fn the_number_of_leaves_in_a_solid_is_limited() {
    let tree = |n: usize| format!("(tree: Union([{}]))", vec!["Object(\"x\")"; n].join(", "));
    let e = parse(&with_solids(&tree(32769), 1), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some(
            "scenes/bad.ron:10:12: solids[0].tree: a solid may use at most 32768 objects, got 32769"
        )
    );
    let e = parse(&with_solids(&tree(32768), 1), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some("scenes/bad.ron:10:19: solids[0].tree[0]: no object is named \"x\"")
    );
}

/// Solids are checked after every object, each tree in pre-order: an operator before its
/// operands, operands left to right.
#[test]
fn solids_are_checked_after_objects_in_pre_order() {
    let text = with_solids(
        "(tree: Difference(Intersection([Object(\"nope\"), Object(\"ball\")]), Union([Object(\"ball\")])))",
        1,
    );
    let shown = |text: &str| parse(text, Path::new(FILE)).err().map(|e| e.to_string());
    assert_eq!(
        shown(&text).as_deref(),
        Some("scenes/bad.ron:10:37: solids[0].tree[0][0]: no object is named \"nope\"")
    );
    let bad_object = text.replacen("material:", "glass: Some(2.0), material:", 1);
    assert_eq!(
        shown(&bad_object).as_deref(),
        Some("scenes/bad.ron:7:55: objects[0].glass: must be in [0, 1], got 2")
    );
    // With that name fixed, the second use of "ball" in the first operand comes before the
    // one-operand Union that is the second.
    let text = text.replacen("Object(\"nope\")", "Object(\"ball\")", 1);
    assert_eq!(
        shown(&text).as_deref(),
        Some(
            "scenes/bad.ron:10:53: solids[0].tree[0][1]: object \"ball\" is already used by solids[0] (at solids[0].tree[0][0])"
        )
    );
}

/// Object names in messages are escaped and clipped, so a message stays short and one line.
#[test]
fn operand_names_in_messages_are_clipped_and_escaped() {
    let long = "n".repeat(10_000);
    let text = with_solids(&format!("(tree: Union([Object(\"{long}\"), Object(\"ball\")]))"), 1);
    let e = parse(&text, Path::new(FILE)).err().unwrap_or_else(|| panic!("accepted"));
    assert!(e.to_string().chars().count() < 200, "{e}");
    assert_eq!(e.field, "solids[0].tree[0]");
    let text = with_solids("(tree: Union([Object(\"a\\nb\"), Object(\"ball\")]))", 1);
    let e = parse(&text, Path::new(FILE)).err().unwrap_or_else(|| panic!("accepted"));
    assert_eq!(e.message, "no object is named \"a\\nb\"");
}

/// `load` shows the case `name`, written to the file `file`, as a bad scene (exit code 2) on
/// one line ending in `tail`.
fn assert_load_shows(name: &str, file: &str, tail: &str) {
    let case = case(name);
    let path = common::temp_file(file, BASE.replacen(case.from, case.to, 1).as_bytes());
    let shown = common::load_bad(&path).to_string();
    assert!(shown.ends_with(tail), "{shown}");
}

/// A bad solid is a bad scene for `load` too: one line, exit code 2.
#[test]
fn a_bad_solid_is_exit_code_2() {
    assert_load_shows(
        "disk operand",
        "bad-solid.ron",
        ":11:46: solids[0].tree[1]: object \"plate\" is not closed (Disk); CSG operands must be closed solids",
    );
}

/// Object and deformation keys are checked against the camera's shutter, wherever it is.
#[test]
fn object_keys_follow_the_shutter() {
    let with = |shutter: &str, motion: &str| {
        let text = BASE
            .replacen("yon: 100.0)", &format!("yon: 100.0, shutter: {shutter})"), 1)
            .replacen("material:", &format!("motion: [{motion}], material:"), 1);
        parse(&text, Path::new(FILE)).map(|_| ()).map_err(|e| e.to_string())
    };
    let keys = |a: &str, b: &str| {
        format!("(time: {a}, transform: []), (time: {b}, transform: [Translate((1.0, 0.0, 0.0))])")
    };
    #[rustfmt::skip]
    let cases = [
        // Keys at both ends of a shifted shutter are inside it; outside it they are not.
        ("(open: 1.0, close: 2.0)", ("1.0", "2.0"), None),
        ("(open: 1.0, close: 2.0)", ("0.0", "2.0"), Some("scenes/bad.ron:7:64: objects[0].motion[0].time: motion key time 0 is outside the shutter [1, 2]")),
        ("(open: 1.0, close: 2.0)", ("1.0", "2.5"), Some("scenes/bad.ron:7:92: objects[0].motion[1].time: motion key time 2.5 is outside the shutter [1, 2]")),
        // A closed shutter (no blur): every key at the opening time, none after.
        ("(open: 0.5, close: 0.5)", ("0.5", "0.5"), None),
        ("(open: 0.5, close: 0.5)", ("0.5", "0.75"), Some("scenes/bad.ron:7:92: objects[0].motion[1].time: motion key time 0.75 is outside the shutter [0.5, 0.5]")),
        // An open shutter needs strictly increasing times.
        ("(open: 0.0, close: 1.0)", ("0.5", "0.5"), Some("scenes/bad.ron:7:92: objects[0].motion[1].time: keys must be in increasing time order, got 0.5 after 0.5")),
    ];
    for (shutter, (a, b), error) in cases {
        let want = error.map_or(Ok(()), |e| Err(e.to_string()));
        assert_eq!(with(shutter, &keys(a, b)), want, "shutter {shutter}, keys at {a} and {b}");
    }
}

/// A bad motion key is a bad scene for `load` too: one line, exit code 2.
#[test]
fn a_bad_motion_key_is_exit_code_2() {
    assert_load_shows(
        "transform motion keys out of order",
        "bad-motion.ron",
        ":7:120: objects[0].motion[2].time: keys must be in increasing time order, got 0.5 after 0.7",
    );
}

/// Every shape, light and material keeps its path when the object is not the first.
#[test]
fn paths_index_lists() {
    let text = BASE.replacen(
        "  ],",
        "    (shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (shape: Disk(radius: -2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],",
        1,
    );
    let e = parse(&text, Path::new(FILE)).err().map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("scenes/bad.ron:9:26: objects[2].shape.radius: must be > 0, got -2")
    );
}

/// Comments and strings holding brackets do not disturb positions.
#[test]
fn positions_survive_comments_and_strings() {
    let text = BASE.replacen("(name: \"ball\"", "(name: \"b(a)l[l]\" /* ( [ */", 1).replacen(
        "radius: 1.0",
        "// radius: 2.0\n      radius: -3.0",
        1,
    );
    let e = parse(&text, Path::new(FILE)).err().map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("scenes/bad.ron:8:15: objects[0].shape.radius: must be > 0, got -3")
    );
}

#[test]
fn new_geometry_messages() {
    assert_eq!(
        shown("nurbs knots decreasing"),
        "scenes/bad.ron:7:76: objects[0].shape.uknot[3]: must not decrease, got 0.5 after 1"
    );
    assert_eq!(
        shown("bicubic patch mesh with 5 points along u"),
        "scenes/bad.ron:7:56: objects[0].shape.nu: a nonperiodic bicubic mesh needs 4 + k * step points (step 3), got 5"
    );
    assert_eq!(
        shown("nurbs umin before the valid range"),
        "scenes/bad.ron:7:88: objects[0].shape.umin: must be >= uknot[1] (0), the start of the valid range, got -0.5"
    );
    assert_eq!(
        shown("hyperboloid operand"),
        "scenes/bad.ron:10:42: solids[0].tree[1]: object \"hyp\" is not closed (Hyperboloid); CSG operands must be closed solids"
    );
}

/// The exact text of the errors of the camera's screen window, an object's shading rate and
/// light set, the spot light and the metal material.
#[test]
fn exact_messages_of_the_renderman_fields() {
    assert_eq!(
        shown("screen window right not above left"),
        "scenes/bad.ron:3:100: camera.screen_window[1]: must be > left (-1), got -2"
    );
    assert_eq!(
        shown("screen window top equal to bottom"),
        "scenes/bad.ron:3:110: camera.screen_window[3]: must be > bottom (1), got 1"
    );
    assert_eq!(
        shown("object shading rate 0"),
        "scenes/bad.ron:7:62: objects[0].shading_rate: must be > 0, got 0"
    );
    assert_eq!(
        shown("light set index out of range"),
        "scenes/bad.ron:7:65: objects[0].lights[1]: index 2 is out of range: the scene has 2 lights"
    );
    assert_eq!(
        shown("light set with a light twice"),
        "scenes/bad.ron:7:68: objects[0].lights[2]: light 1 is listed twice (also at lights[0])"
    );
    assert_eq!(
        shown("spot cone delta above the cone angle"),
        "scenes/bad.ron:5:117: lights[1].cone_delta: must be <= cone_angle (10), got 12"
    );
    assert_eq!(
        shown("metal roughness 0"),
        "scenes/bad.ron:7:99: objects[0].material.roughness: must be > 0, got 0"
    );
}

//! The image size and the camera: eye, look_at, up, projection, field of view, screen window, clipping, shutter and its shapes, lens, motion keys, and the view the renderer builds from them.

use super::Case;

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "unknown field", from: "height: 480)", to: "height: 480, depth: 8)", field: "image.depth", at: Some((2, 36)) },
    Case { name: "missing required field", from: "width: 640, height: 480)", to: "width: 640)", field: "image.height", at: Some((2, 21)) },
    Case { name: "missing required section", from: "  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), fov: 35.0, hither: 0.1, yon: 100.0),\n", to: "", field: "camera", at: Some((8, 1)) },
    Case { name: "duplicate field", from: "height: 480)", to: "height: 480, width: 2)", field: "image.width", at: Some((2, 36)) },
    Case { name: "wrong type", from: "width: 640", to: "width: \"640\"", field: "image.width", at: Some((2, 18)) },
    Case { name: "negative integer", from: "width: 640", to: "width: -640", field: "image.width", at: Some((2, 18)) },
    Case { name: "wrong tuple length", from: "(0.0, 1.0, -10.0)", to: "(0.0, 1.0)", field: "camera.eye", at: Some((3, 26)) },
    Case { name: "lens without Some", from: "yon: 100.0)", to: "yon: 100.0, lens: (focal_length: 1.0, f_stop: 2.8, focal_distance: 8.0))", field: "camera.lens", at: Some((3, 104)) },
    Case { name: "width 0", from: "width: 640", to: "width: 0", field: "image.width", at: Some((2, 18)) },
    Case { name: "height 0", from: "height: 480", to: "height: 0", field: "image.height", at: Some((2, 31)) },
    Case { name: "width too large", from: "width: 640", to: "width: 70000", field: "image.width", at: Some((2, 18)) },
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
    Case { name: "NaN fov", from: "fov: 35.0", to: "fov: NaN", field: "camera.fov", at: Some((3, 67)) },
    Case { name: "inf yon", from: "yon: 100.0", to: "yon: inf", field: "camera.yon", at: Some((3, 91)) },
    Case { name: "-inf eye", from: "-10.0", to: "-inf", field: "camera.eye[2]", at: Some((3, 28)) },
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
    Case { name: "closed shutter with a key after open", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 0.5, close: 0.5), motion: [(time: 0.5, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 0.6, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[1].time", at: Some((3, 211)) },
    Case { name: "key before a shifted shutter", from: "yon: 100.0)", to: "yon: 100.0, shutter: (open: 1.0, close: 2.0), motion: [(time: 0.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)), (time: 2.0, eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0))])", field: "camera.motion[0].time", at: Some((3, 148)) },
    Case { name: "screen window right not above left", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, -2.0, -1.0, 1.0))", field: "camera.screen_window[1]", at: Some((3, 100)) },
    Case { name: "screen window top equal to bottom", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, 1.0, 1.0, 1.0))", field: "camera.screen_window[3]", at: Some((3, 110)) },
    Case { name: "screen window NaN", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((NaN, 1.0, -1.0, 1.0))", field: "camera.screen_window[0]", at: Some((3, 94)) },
    Case { name: "screen window inf", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, inf, -1.0, 1.0))", field: "camera.screen_window[1]", at: Some((3, 100)) },
    Case { name: "screen window with 3 values", from: "fov: 35.0", to: "fov: 35.0, screen_window: Some((-1.0, 1.0, -1.0))", field: "camera.screen_window", at: Some((3, 109)) },
    Case { name: "screen window without Some", from: "fov: 35.0", to: "fov: 35.0, screen_window: (-1.0, 1.0, -1.0, 1.0)", field: "camera.screen_window", at: Some((3, 88)) },
    Case { name: "unknown projection", from: "fov: 35.0", to: "projection: Fisheye, fov: 35.0", field: "camera.projection", at: Some((3, 74)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}

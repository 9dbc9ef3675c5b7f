//! The rules of the view: `image` size, then `camera` in field order (the screen window
//! after `fov`), its motion keys last.
//!
//! Invariant: every `f32` is checked finite before it is compared; the orientation test is
//! done in `f64`.

use glam::DVec3;

use super::keys::keys;
use super::primitives::{
    Check, Interval, above, dvec, fail, finite, finite_all, int_in, parallel, positive, within,
};
use crate::model::{Camera, Image, ShutterShape, V3};

pub(super) fn image(image: &Image) -> Check {
    int_in("image.width", image.width, 1, 65536)?;
    int_in("image.height", image.height, 1, 65536)
}

pub(super) fn camera(cam: &Camera) -> Check {
    finite_all("camera.eye", &cam.eye)?;
    finite_all("camera.look_at", &cam.look_at)?;
    finite_all("camera.up", &cam.up)?;
    within("camera.fov", cam.fov, Interval::open(0.0, 180.0), " degrees")?;
    if let Some(window) = &cam.screen_window {
        screen_window("camera.screen_window", window)?;
    }
    positive("camera.hither", cam.hither)?;
    finite("camera.yon", cam.yon)?;
    above("camera.yon", cam.yon, "hither", cam.hither)?;
    orientation("camera", &cam.eye, &cam.look_at, &cam.up)?;
    finite("camera.shutter.open", cam.shutter.open)?;
    finite("camera.shutter.close", cam.shutter.close)?;
    if cam.shutter.close < cam.shutter.open {
        return fail(
            "camera.shutter.close",
            format!("must be >= shutter.open ({}), got {}", cam.shutter.open, cam.shutter.close),
        );
    }
    if let ShutterShape::Gradual { ramp } = cam.shutter.shape {
        within("camera.shutter.shape.ramp", ramp, Interval::open_closed(0.0, 0.5), "")?;
    }
    if let Some(lens) = &cam.lens {
        positive("camera.lens.focal_length", lens.focal_length)?;
        positive("camera.lens.f_stop", lens.f_stop)?;
        positive("camera.lens.focal_distance", lens.focal_distance)?;
    }
    keys(
        "camera.motion",
        &cam.motion,
        |k| k.time,
        &cam.shutter,
        |i, key| {
            let at = format!("camera.motion[{i}]");
            finite_all(&format!("{at}.eye"), &key.eye)?;
            finite_all(&format!("{at}.look_at"), &key.look_at)?;
            finite_all(&format!("{at}.up"), &key.up)?;
            orientation(&at, &key.eye, &key.look_at, &key.up)
        },
    )
}

/// A screen window `[left, right, bottom, top]`: finite, `left < right`, `bottom < top`.
fn screen_window(at: &str, w: &[f32; 4]) -> Check {
    finite_all(at, w)?;
    let [left, right, bottom, top] = *w;
    above(&format!("{at}[1]"), right, "left", left)?;
    above(&format!("{at}[3]"), top, "bottom", bottom)
}

/// The camera rules on `eye`, `look_at` and `up` (all finite), reported under `at`.
fn orientation(at: &str, eye: &V3, look_at: &V3, up: &V3) -> Check {
    if eye == look_at {
        return fail(format!("{at}.look_at"), "must differ from eye");
    }
    let view = dvec(look_at) - dvec(eye);
    let up = dvec(up);
    if up == DVec3::ZERO {
        return fail(format!("{at}.up"), "must be non-zero");
    }
    if parallel(up, view) {
        return fail(
            format!("{at}.up"),
            "must not be parallel to the view direction (look_at - eye)",
        );
    }
    Ok(())
}

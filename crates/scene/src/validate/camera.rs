//! The rules of the view: `image` size, then `camera` in field order, its motion keys last.
//!
//! Invariant: every `f32` is checked finite before it is compared; the orientation test is
//! done in `f64`.

use glam::DVec3;

use super::keys::keys;
use super::primitives::{Check, dvec, fail, finite, finite_all, int_in, positive};
use crate::model::{Camera, Image, ShutterShape, V3};

pub(super) fn image(image: &Image) -> Check {
    int_in("image.width", image.width, 1, 65536)?;
    int_in("image.height", image.height, 1, 65536)
}

pub(super) fn camera(cam: &Camera) -> Check {
    finite_all("camera.eye", &cam.eye)?;
    finite_all("camera.look_at", &cam.look_at)?;
    finite_all("camera.up", &cam.up)?;
    finite("camera.fov", cam.fov)?;
    if !(cam.fov > 0.0 && cam.fov < 180.0) {
        return fail("camera.fov", format!("must be in (0, 180) degrees, got {}", cam.fov));
    }
    positive("camera.hither", cam.hither)?;
    finite("camera.yon", cam.yon)?;
    if cam.yon <= cam.hither {
        return fail("camera.yon", format!("must be > hither ({}), got {}", cam.hither, cam.yon));
    }
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
        finite("camera.shutter.shape.ramp", ramp)?;
        if !(ramp > 0.0 && ramp <= 0.5) {
            return fail("camera.shutter.shape.ramp", format!("must be in (0, 0.5], got {ramp}"));
        }
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
    if up.cross(view).length() <= 1e-6 * up.length() * view.length() {
        return fail(
            format!("{at}.up"),
            "must not be parallel to the view direction (look_at - eye)",
        );
    }
    Ok(())
}

//! The rules of the view: `image` size, then `camera` in field order (the screen window
//! after `fov`, then the raster mapping they make), its motion keys last.
//!
//! Invariant: every `f32` is checked finite before it is compared; the orientation test is
//! done in `f64`, then the renderer's own `f32` construction ([`crate::view`]) must succeed
//! and give finite numbers, so a camera that passes always has a basis and a projection.

use glam::{DVec3, Vec3};

use super::keys::keys;
use super::primitives::{
    Check, Interval, above, dvec, fail, finite, finite_all, int_in, parallel, positive, within,
};
use crate::model::{Camera, Image, Projection, ShutterShape, V3};
use crate::view::{self, ViewError};

pub(super) fn image(image: &Image) -> Check {
    int_in("image.width", image.width, 1, 65536)?;
    int_in("image.height", image.height, 1, 65536)?;
    if let Some(c) = &image.crop {
        finite_all("image.crop", c)?;
        let unit = |v: f32| (0.0..=1.0).contains(&v);
        if !c.iter().copied().all(unit) || c[0] >= c[1] || c[2] >= c[3] {
            return fail(
                "image.crop",
                format!("expected [xmin, xmax, ymin, ymax] with 0 <= min < max <= 1, got {c:?}"),
            );
        }
        let [x0, x1, y0, y1] = image.crop_pixels();
        if x0 >= x1 || y0 >= y1 {
            return fail(
                "image.crop",
                format!("{c:?} selects no pixel of the {} x {} image", image.width, image.height),
            );
        }
    }
    Ok(())
}

pub(super) fn camera(cam: &Camera, image: &Image) -> Check {
    finite_all("camera.eye", &cam.eye)?;
    finite_all("camera.look_at", &cam.look_at)?;
    finite_all("camera.up", &cam.up)?;
    within("camera.fov", cam.fov, Interval::open(0.0, 180.0), " degrees")?;
    if let Some(window) = &cam.screen_window {
        screen_window("camera.screen_window", window)?;
    }
    let (_, scale) = projection(cam, image)?;
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
    let length = cam.shutter.close - cam.shutter.open;
    if !length.is_finite() {
        return fail(
            "camera.shutter.close",
            format!(
                "the shutter is open from {:?} to {:?}, longer than single precision can hold \
                 (close - open is {length:?})",
                cam.shutter.open, cam.shutter.close
            ),
        );
    }
    if let ShutterShape::Gradual { ramp } = cam.shutter.shape {
        within("camera.shutter.shape.ramp", ramp, Interval::open_closed(0.0, 0.5), "")?;
    }
    if let Some(lens) = &cam.lens {
        positive("camera.lens.focal_length", lens.focal_length)?;
        positive("camera.lens.f_stop", lens.f_stop)?;
        positive("camera.lens.focal_distance", lens.focal_distance)?;
        if cam.projection == Projection::Perspective {
            blur(lens, scale)?;
        }
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

/// The raster mapping of the projection and screen window on the image ([`view::raster_mapping`],
/// as the renderer computes it): its centre finite and its scale finite and a normal `f32`
/// (a denormal or zero scale divides to infinity). Returns the mapping.
fn projection(cam: &Camera, image: &Image) -> Result<(glam::Vec2, glam::Vec2), super::Issue> {
    let (centre, scale) = view::raster_mapping(cam, image.width as f32, image.height as f32);
    if centre.is_finite() && scale.is_finite() && scale.min_element() >= f32::MIN_POSITIVE {
        return Ok((centre, scale));
    }
    let (at, what) = match cam.screen_window {
        Some(_) => ("camera.screen_window", "the window is too small or too large"),
        None => ("camera.fov", "the field of view is too narrow"),
    };
    fail(
        at,
        format!(
            "the raster mapping has scale ({:?}, {:?}) and centre ({:?}, {:?}) in pixels, not \
             finite normal single-precision numbers: {what}",
            scale.x, scale.y, centre.x, centre.y
        ),
    )
    .map(|()| (centre, scale))
}

/// Largest depth-of-field constant allowed: the lens radius in raster pixels (and that over the
/// focal distance) stays this far below `f32::MAX`, so the blur of any depth stays finite.
const MAX_BLUR: f64 = 1e30;

/// A thin lens on a perspective camera: its radius ([`crate::Lens::radius`]) finite, and its
/// blur constants (the radius in raster pixels, and that over the focal distance: the circle of
/// confusion is `radius * k * (1/z - 1/focal_distance)`) at most [`MAX_BLUR`].
fn blur(lens: &crate::model::Lens, scale: glam::Vec2) -> Check {
    let radius = lens.radius();
    if !radius.is_finite() {
        return fail(
            "camera.lens",
            format!(
                "the lens radius 0.5 * focal_length / f_stop is {radius:?}: more than single \
                 precision can hold"
            ),
        );
    }
    let k = f64::from(scale.max_element());
    let a = f64::from(radius) * k;
    let b = a / f64::from(lens.focal_distance);
    if a > MAX_BLUR || b > MAX_BLUR {
        return fail(
            "camera.lens",
            format!(
                "the lens blurs by up to {:?} pixels (radius {radius:?} at {:?} pixels per unit, \
                 focal distance {:?}): more than {MAX_BLUR:e}",
                a.max(b) as f32,
                k as f32,
                lens.focal_distance
            ),
        );
    }
    Ok(())
}

/// The camera rules on `eye`, `look_at` and `up` (all finite), reported under `at`: in `f64`
/// the view direction and `up` non-zero and not parallel, then the renderer's `f32` basis
/// ([`view::basis`]) exists and its world-to-camera matrix is finite.
fn orientation(at: &str, eye: &V3, look_at: &V3, up: &V3) -> Check {
    if eye == look_at {
        return fail(format!("{at}.look_at"), "must differ from eye");
    }
    let view = dvec(look_at) - dvec(eye);
    let up64 = dvec(up);
    if up64 == DVec3::ZERO {
        return fail(format!("{at}.up"), "must be non-zero");
    }
    if parallel(up64, view) {
        return fail(
            format!("{at}.up"),
            "must not be parallel to the view direction (look_at - eye)",
        );
    }
    let (eye, look_at, up) = (Vec3::from(*eye), Vec3::from(*look_at), Vec3::from(*up));
    match view::basis(eye, look_at, up) {
        Err(ViewError::NoDirection) => {
            let d = look_at - eye;
            fail(
                format!("{at}.look_at"),
                format!(
                    "look_at - eye is ({:?}, {:?}, {:?}) in single precision, whose length \
                     {}: the view has no direction",
                    d.x,
                    d.y,
                    d.z,
                    if d.length_squared() == 0.0 { "underflows to 0" } else { "overflows" }
                ),
            )
        }
        Err(ViewError::UpParallel) => fail(
            format!("{at}.up"),
            "is parallel to the view direction in single precision (up x (look_at - eye) \
             rounds to nothing beside up): the camera has no basis",
        ),
        Ok(basis) if !basis.world_to_camera(eye).is_finite() => fail(
            format!("{at}.eye"),
            "is too far from the origin: the world-to-camera matrix overflows single precision",
        ),
        Ok(_) => Ok(()),
    }
}

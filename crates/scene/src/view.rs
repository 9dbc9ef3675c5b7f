//! The camera's view as the renderer builds it: the orthonormal basis of `eye`, `look_at` and
//! `up` ([`basis`]), the world-to-camera matrix ([`ViewBasis::world_to_camera`]) and the
//! raster mapping of the projection and screen window ([`raster_mapping`]).
//!
//! The dicer's camera setup computes these with the functions here, and validation refuses a
//! camera for which they fail or give numbers that are not finite, so the two cannot disagree:
//! a validated camera always has a basis and a finite projection.
//!
//! Invariants: everything is computed in `f32`, exactly as the renderer uses it (validation's
//! own geometric rules work in `f64`; these catch what only single precision loses: view
//! directions whose length underflows or overflows, an `up` that rounds parallel to the view).
//! Camera space is +x right, +y up, +z forward; raster space is pixels with y down.

use glam::{DVec2, Mat4, Vec2, Vec3, Vec4};

use crate::model::{Camera, Projection};

/// Relative size below which `cross(up, forward)` counts as zero (up parallel to the view).
pub const PARALLEL_EPS: f32 = 1e-7;

/// An orthonormal camera basis in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewBasis {
    /// Camera +x.
    pub right: Vec3,
    /// Camera +y.
    pub up: Vec3,
    /// Camera +z, the view direction.
    pub forward: Vec3,
}

/// Why a view has no basis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewError {
    /// `look_at - eye` cannot be normalised in `f32`: the points coincide, or are a
    /// denormal apart (the length underflows), or so far apart that the length overflows.
    NoDirection,
    /// `up` is parallel to the view direction, or zero, after rounding to `f32`.
    UpParallel,
}

/// The camera basis of the view from `eye` towards `look_at` with `up` (which need not be
/// perpendicular to the view direction): `forward` the unit view direction, `right` the unit
/// `up x forward`, `up` their cross product.
pub fn basis(eye: Vec3, look_at: Vec3, up: Vec3) -> Result<ViewBasis, ViewError> {
    let forward = (look_at - eye).try_normalize().ok_or(ViewError::NoDirection)?;
    let side = up.cross(forward);
    if side.length() <= PARALLEL_EPS * up.length() {
        return Err(ViewError::UpParallel);
    }
    let right = side.try_normalize().ok_or(ViewError::UpParallel)?;
    let up = forward.cross(right);
    Ok(ViewBasis { right, up, forward })
}

impl ViewBasis {
    /// The world-to-camera matrix of this basis seen from `eye` (rigid: its rows are right,
    /// up and forward, and `eye` maps to the origin).
    pub fn world_to_camera(&self, eye: Vec3) -> Mat4 {
        let ViewBasis { right, up, forward } = *self;
        Mat4::from_cols(
            Vec4::new(right.x, up.x, forward.x, 0.0),
            Vec4::new(right.y, up.y, forward.y, 0.0),
            Vec4::new(right.z, up.z, forward.z, 0.0),
            Vec4::new(-right.dot(eye), -up.dot(eye), -forward.dot(eye), 1.0),
        )
    }
}

/// The raster mapping `(centre, scale)` of `cam` on a `width x height` image: raster position
/// `centre + (kx sx, -ky sy)` of screen position `(sx, sy)`, where screen space is
/// `(x/z, y/z) / tan(fov/2)` (perspective) or `(x, y)` (orthographic) and the screen window
/// `[left, right, bottom, top]` fills the image. Without a screen window the window is
/// RenderMan's default (the shorter side spans [-1, 1]) and the arithmetic is the renderer's
/// from before screen windows (`centre = size / 2`, `k = (S/2) / tan(fov/2)`), bit for bit.
pub fn raster_mapping(cam: &Camera, width: f32, height: f32) -> (Vec2, Vec2) {
    let perspective = cam.projection == Projection::Perspective;
    let Some([left, right, bottom, top]) = cam.screen_window else {
        let half_short = 0.5 * width.min(height);
        let k =
            if perspective { half_short / (0.5 * cam.fov.to_radians()).tan() } else { half_short };
        return (Vec2::new(0.5 * width, 0.5 * height), Vec2::splat(k));
    };
    // Screen x = left at raster 0 and right at `width`; y = top at raster 0, bottom at
    // `height`. In f64, where the window's extent is exact and nothing overflows.
    let (left, right, bottom, top) =
        (f64::from(left), f64::from(right), f64::from(bottom), f64::from(top));
    let per_screen =
        DVec2::new(f64::from(width) / (right - left), f64::from(height) / (top - bottom));
    let centre = DVec2::new(-left * per_screen.x, top * per_screen.y);
    let scale = if perspective {
        per_screen / (0.5 * f64::from(cam.fov).to_radians()).tan()
    } else {
        per_screen
    };
    (centre.as_vec2(), scale.as_vec2())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bases_are_orthonormal_and_left_handed() {
        let b = basis(Vec3::ZERO, Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 2.0, 0.0));
        assert_eq!(b, Ok(ViewBasis { right: Vec3::X, up: Vec3::Y, forward: Vec3::Z }));
        let m = b.map(|b| b.world_to_camera(Vec3::new(1.0, 2.0, 3.0)));
        assert_eq!(m.map(|m| m.transform_point3(Vec3::new(1.0, 2.0, 3.0))), Ok(Vec3::ZERO));
    }

    /// What single precision loses: a denormal or an overflowing view direction, and an up
    /// vector whose cross product with it underflows.
    #[test]
    fn degenerate_views_in_f32() {
        let up = Vec3::Y;
        assert_eq!(basis(Vec3::ZERO, Vec3::ZERO, up), Err(ViewError::NoDirection));
        assert_eq!(basis(Vec3::ZERO, Vec3::new(0.0, 0.0, 1e-40), up), Err(ViewError::NoDirection));
        let far = Vec3::new(0.0, 0.0, 2e19);
        assert_eq!(basis(-far, far, up), Err(ViewError::NoDirection));
        assert!(basis(Vec3::ZERO, far * 0.5, up).is_ok());
        let z = Vec3::new(0.0, 0.0, 1.0);
        assert_eq!(basis(Vec3::ZERO, z, Vec3::ZERO), Err(ViewError::UpParallel));
        assert_eq!(basis(Vec3::ZERO, z, Vec3::new(1e-30, 1e-30, 0.0)), Err(ViewError::UpParallel));
        assert_eq!(basis(Vec3::ZERO, z, Vec3::new(1e-8, 0.0, 1.0)), Err(ViewError::UpParallel));
        assert!(basis(Vec3::ZERO, z, Vec3::new(1e-6, 0.0, 1.0)).is_ok());
    }
}

//! Depth-of-field constants (`VisCameraSetup`) and bound growth (`bounddof`).
//!
//! A point at eye depth `z`, seen from lens position `(lx, ly)` (in units of the lens
//! radius), moves on screen by `lx * (x_a / z + x_b)`, `ly * (y_a / z + y_b)` pixels
//! (Appendix A, comment of `VisCameraSetup`), where `x_a = R * a/f` is the lens radius
//! times the raster-pixel change per unit eye x at depth 1, and `x_b = -x_a / focal_distance`.

/// `Dofx_a, Dofx_b, Dofy_a, Dofy_b` of Appendix A.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LensSetup {
    /// `Dofx_a`: pixels per lens-radius unit at depth 1, x.
    pub x_a: f32,
    /// `Dofx_b = -Dofx_a / focal_distance`.
    pub x_b: f32,
    /// `Dofy_a`.
    pub y_a: f32,
    /// `Dofy_b = -Dofy_a / focal_distance`.
    pub y_b: f32,
}

impl LensSetup {
    /// Port of `VisCameraSetup`: `ax_per_unit`, `ay_per_unit` are the raster displacement of
    /// eye point B = (1, 1, 1) from A = (0, 0, 1), i.e. `a/f` and `b/f` of the perspective
    /// matrix (signed: raster y grows downward, so `ay_per_unit` is negative for a y-up eye).
    pub fn new(
        lens_radius: f32,
        focal_distance: f32,
        ax_per_unit: f32,
        ay_per_unit: f32,
    ) -> LensSetup {
        let x_a = lens_radius * ax_per_unit;
        let y_a = lens_radius * ay_per_unit;
        LensSetup { x_a, x_b: -x_a / focal_distance, y_a, y_b: -y_a / focal_distance }
    }

    /// Screen displacement per unit lens offset at depth `z`: `(x_a/z + x_b, y_a/z + y_b)`.
    #[inline]
    pub fn coc(&self, z: f32) -> (f32, f32) {
        (self.x_a / z + self.x_b, self.y_a / z + self.y_b)
    }

    /// Port of `bounddof`: grow an x/y box whose depth range is `[zmin, zmax]` by the
    /// largest lens displacement over that range (monotone in 1/z, so an endpoint holds it),
    /// for lens offsets with `|l| <= 1`. Depths are clamped to `[hither, yon]` as in the
    /// original; the dicer never emits vertices in front of hither/2, so the clamp only
    /// matters for hither/yon-crossing micropolygons, which are clipped per sample anyway.
    pub fn grow(&self, lo: &mut [f32; 3], hi: &mut [f32; 3], hither: f32, yon: f32) {
        let zmin = lo[2].max(hither);
        let zmax = hi[2].min(yon).max(zmin);
        let (x1, y1) = self.coc(zmin);
        let (x2, y2) = self.coc(zmax);
        let bx = x1.abs().max(x2.abs());
        let by = y1.abs().max(y2.abs());
        lo[0] -= bx;
        hi[0] += bx;
        lo[1] -= by;
        hi[1] += by;
    }
}

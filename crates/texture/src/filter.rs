//! Footprint filtering: an anisotropic trilinear approximation of the box filter over a
//! micropolygon's footprint in texture space, RenderMan's `texture()` with its `"width"`.
//!
//! The footprint is the axis-aligned rectangle of extents `ds x dt` centred at `(s, t)`,
//! which is `fx = ds * W` by `fy = dt * H` texels of level 0 (`W x H`). Its minor side,
//! raised to at least `major / MAX_PROBES` so that the probe count stays bounded, picks the
//! level: `lod = log2(minor)`, clamped to the pyramid, read trilinearly (bilinear in the two
//! levels around `lod`, blended by its fraction). Along the major side `n = ceil(major /
//! minor)` such probes (at most [`MAX_PROBES`]) are spread evenly, at the centres of `n`
//! equal parts of the footprint, and averaged. A footprint below one texel reads level 0
//! bilinearly at `(s, t)`: a texture seen at its own resolution reproduces its texels at
//! their centres.
//!
//! Texel `(x, y)` of a `w x h` level covers `[x / w, (x + 1) / w] x [y / h, (y + 1) / h]`
//! in texture space, its centre at `((x + 0.5) / w, (y + 0.5) / h)`; `t` runs down the image.
//!
//! Invariants: every result is a convex combination of texels (and of zeros with `Black`),
//! so it lies within the texture's per-channel range; finite for finite input; a non-finite
//! coordinate reads as 0.

use std::sync::Arc;

use crate::{Texture, TextureSystem, Wrap};

/// Most probes along a footprint's major side (its largest anisotropy at full sharpness).
pub const MAX_PROBES: u32 = 16;

/// Reads texels through the system's cache, keeping the tile it read last.
pub struct Reader<'a> {
    system: &'a TextureSystem,
    last: Option<(u64, Arc<[f32]>)>,
}

impl<'a> Reader<'a> {
    /// A reader of `system`'s tiles.
    pub fn new(system: &'a TextureSystem) -> Reader<'a> {
        Reader { system, last: None }
    }

    /// Texel `(x, y)` (in range) of level `level` of `texture`.
    pub(crate) fn texel(&mut self, texture: &Texture, level: usize, x: u32, y: u32) -> [f32; 4] {
        let l = &texture.levels[level];
        let (tx, ty) = (x / l.tile_w, y / l.tile_h);
        let tile = l.first_tile + u64::from(ty) * u64::from(l.tiles_x) + u64::from(tx);
        let texels = match &self.last {
            Some((t, texels)) if *t == tile => texels,
            _ => &self.last.insert((tile, self.system.tile(texture, l, tile))).1,
        };
        let k = 4 * ((y % l.tile_h) as usize * l.tile_w as usize + (x % l.tile_w) as usize);
        if k + 4 > texels.len() {
            return [0.0; 4];
        }
        [texels[k], texels[k + 1], texels[k + 2], texels[k + 3]]
    }

    /// Texel `(x, y)` of a level `w x h`, possibly out of range, through `wrap` (`None`:
    /// black).
    fn wrapped(
        &mut self,
        texture: &Texture,
        level: usize,
        (x, y): (i64, i64),
        wrap: [Wrap; 2],
    ) -> [f32; 4] {
        let l = &texture.levels[level];
        let one = |v: i64, n: i64, wrap: Wrap| match wrap {
            Wrap::Periodic => Some(v.rem_euclid(n)),
            Wrap::Clamp => Some(v.clamp(0, n - 1)),
            Wrap::Black => (0..n).contains(&v).then_some(v),
        };
        let x = one(x, i64::from(l.width), wrap[0]);
        let y = one(y, i64::from(l.height), wrap[1]);
        let (Some(x), Some(y)) = (x, y) else { return [0.0; 4] };
        self.texel(texture, level, x as u32, y as u32)
    }

    /// Bilinear interpolation of level `level` at texture coordinates `(s, t)`.
    pub(crate) fn bilinear(
        &mut self,
        texture: &Texture,
        level: usize,
        s: f32,
        t: f32,
        wrap: [Wrap; 2],
    ) -> [f32; 4] {
        let l = &texture.levels[level];
        let x = f64::from(s) * f64::from(l.width) - 0.5;
        let y = f64::from(t) * f64::from(l.height) - 0.5;
        if !(x.is_finite() && y.is_finite()) {
            return [0.0; 4];
        }
        // Far outside any image: keep the integers in range (wrapping is periodic anyway).
        let (x, y) = (x.clamp(-1e15, 1e15), y.clamp(-1e15, 1e15));
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let a = self.wrapped(texture, level, (x0, y0), wrap);
        let b = self.wrapped(texture, level, (x0 + 1, y0), wrap);
        let c = self.wrapped(texture, level, (x0, y0 + 1), wrap);
        let d = self.wrapped(texture, level, (x0 + 1, y0 + 1), wrap);
        let mut out = [0.0; 4];
        for k in 0..4 {
            let top = a[k] + (b[k] - a[k]) * fx;
            let bottom = c[k] + (d[k] - c[k]) * fx;
            out[k] = top + (bottom - top) * fy;
        }
        out
    }

    /// Trilinear interpolation at `(s, t)` and level of detail `lod` (in levels, >= 0).
    fn trilinear(
        &mut self,
        texture: &Texture,
        lod: f32,
        s: f32,
        t: f32,
        wrap: [Wrap; 2],
    ) -> [f32; 4] {
        let top = texture.levels.len() - 1;
        let lod = lod.clamp(0.0, top as f32);
        let l0 = (lod.floor() as usize).min(top);
        let f = lod - l0 as f32;
        let a = self.bilinear(texture, l0, s, t, wrap);
        if f <= 0.0 || l0 == top {
            return a;
        }
        let b = self.bilinear(texture, l0 + 1, s, t, wrap);
        let mut out = [0.0; 4];
        for k in 0..4 {
            out[k] = a[k] + (b[k] - a[k]) * f;
        }
        out
    }
}

/// The filtered value of `texture` over the footprint `(st, dst)` (see the module).
pub fn lookup(
    texture: &Texture,
    reader: &mut Reader<'_>,
    st: [f32; 2],
    dst: [f32; 2],
    wrap: Wrap,
) -> [f32; 4] {
    lookup_weighted(texture, reader, st, dst, [wrap; 2], |_| 1.0)
}

/// [`lookup`] with a wrap mode per axis, the probes along the footprint's major side weighted
/// by `weight(offset)`, `offset` in `[-0.5, 0.5]` across the footprint (1 for RenderMan's
/// `"box"`; a triangle or a Gaussian for the others, [`crate::lookup`]).
pub fn lookup_weighted(
    texture: &Texture,
    reader: &mut Reader<'_>,
    [s, t]: [f32; 2],
    [ds, dt]: [f32; 2],
    wrap: [Wrap; 2],
    weight: impl Fn(f32) -> f32,
) -> [f32; 4] {
    let base = texture.levels[0];
    let fx = (ds.abs() * base.width as f32).min(1e9);
    let fy = (dt.abs() * base.height as f32).min(1e9);
    let (major, minor) = if fx >= fy { (fx, fy) } else { (fy, fx) };
    if major.is_nan() || major <= 1.0 {
        // Within one texel (or not a number): level 0 at the centre.
        return reader.bilinear(texture, 0, s, t, wrap);
    }
    let minor = minor.max(major / MAX_PROBES as f32).max(1.0);
    let n = ((major / minor).ceil() as u32).clamp(1, MAX_PROBES);
    let lod = minor.log2();
    let mut sum = [0.0f32; 4];
    let mut total = 0.0;
    for k in 0..n {
        let off = (k as f32 + 0.5) / n as f32 - 0.5;
        let (ps, pt) = if fx >= fy { (s + off * ds.abs(), t) } else { (s, t + off * dt.abs()) };
        let v = reader.trilinear(texture, lod, ps, pt, wrap);
        let w = weight(off);
        total += w;
        for c in 0..4 {
            sum[c] += w * v[c];
        }
    }
    sum.map(|v| if total > 0.0 { v / total } else { 0.0 })
}

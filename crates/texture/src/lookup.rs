//! The shading language's lookups (RenderMan Specification 3.2, chapter 15): `texture()` over
//! the four corners of a micropolygon's footprint, `environment()` in a direction,
//! `shadow()` at a point, with their optional parameters.
//!
//! - **texture**: the footprint is the bounding box of the four `(s, t)` corners, scaled about
//!   its centre by `"width"` (`"swidth"`, `"twidth"`), grown by `"blur"` (`"sblur"`,
//!   `"tblur"`, in texture coordinates) and filtered as [`crate::filter`] says, through the
//!   file's wrap modes. `"filter"`: `"box"` (the default) weighs the probes along the
//!   footprint's major side equally, `"triangle"` by `1 - 2|x|`, `"gaussian"` by
//!   `exp(-8 x^2)` (x from -1/2 to 1/2 across the footprint); across the minor side the MIP
//!   level's box does the filtering for every filter. Other names read as `"box"`.
//! - **environment**: a latitude-longitude map takes `s = 1/2 + atan2(y, x) / 2 pi` and
//!   `t = acos(z / |d|) / pi` (z up, as Aqsis and PRMan); a cube-face map the face of the
//!   direction's largest component, laid out `px py pz` above `nx ny nz`. The footprint is
//!   the angle the corner directions span (a longitude step widened by `1 / sin(theta)`).
//! - **shadow**: each corner is carried by the map's world-to-camera matrix (its depth, the
//!   camera-space z) and world-to-screen matrix (its place, `s = (x + 1) / 2`,
//!   `t = (1 - y) / 2`). Percentage-closer filtering: `"samples"` points (default 16),
//!   stratified over the bounding box of the projected corners (scaled by `"width"`, grown by
//!   `"blur"`, at least a texel), each jittered by a hash of its position, compare the point's
//!   depth less `"bias"` (or a value between `"bias0"` and `"bias1"`) with the nearest texel's
//!   depth; the result is the fraction farther (1 in shadow). A point outside the map is lit.
//!
//! Invariants: lookups are pure functions of the map and their arguments (the jitter is a
//! hash, not a random stream); results of texture and environment are convex combinations of
//! texels; shadow results lie in [0, 1].

use crate::filter::{Reader, lookup_weighted};
use crate::prepared::MapKind;
use crate::{TextureId, TextureSystem, Wrap};

/// The optional parameters of a lookup.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// `"sblur"`, `"tblur"` (`"blur"` both): added to the footprint, in texture coordinates.
    pub blur: [f32; 2],
    /// `"swidth"`, `"twidth"` (`"width"` both): the footprint's scale.
    pub width: [f32; 2],
    /// `"filter"`.
    pub filter: String,
    /// `"fill"`: the value of channels the map does not have.
    pub fill: f32,
    /// `"samples"`: shadow samples.
    pub samples: u32,
    /// `"bias"`, or `"bias0"` and `"bias1"`: subtracted from a point's depth before the test.
    pub bias: [f32; 2],
}

impl Default for Options {
    fn default() -> Self {
        Options {
            blur: [0.0; 2],
            width: [1.0; 2],
            filter: "box".into(),
            fill: 0.0,
            samples: 16,
            bias: [0.0; 2],
        }
    }
}

impl Options {
    fn weight(&self) -> fn(f32) -> f32 {
        match self.filter.as_str() {
            "triangle" => |x| 1.0 - 2.0 * x.abs(),
            "gaussian" => |x| (-8.0 * x * x).exp(),
            _ => |_| 1.0,
        }
    }
}

/// The wrap modes of texture `id`: its file's, else periodic.
fn wraps(system: &TextureSystem, id: TextureId) -> [Wrap; 2] {
    let t = system.texture(id);
    t.header.as_ref().and_then(|h| h.wrap).unwrap_or([Wrap::Periodic; 2])
}

fn finite_or(v: f32, or: f32) -> f32 {
    if v.is_finite() { v } else { or }
}

impl TextureSystem {
    /// `texture()` of map `id` over the footprint of four `(s, t)` corners: RGBA.
    pub fn texture_corners(&self, id: TextureId, corners: [[f32; 2]; 4], o: &Options) -> [f32; 4] {
        let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
        for c in corners {
            for k in 0..2 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        let centre = [0, 1].map(|k| 0.25 * corners.iter().map(|c| c[k]).sum::<f32>());
        let extent = [0, 1].map(|k| finite_or((hi[k] - lo[k]) * o.width[k] + o.blur[k].abs(), 0.0));
        self.count_lookup();
        let texture = self.texture(id);
        let mut reader = Reader::new(self);
        lookup_weighted(texture, &mut reader, centre, extent, wraps(self, id), o.weight())
    }

    /// `environment()` of map `id` in the directions `dirs` (one, or four corners): RGBA.
    pub fn environment(&self, id: TextureId, dirs: &[[f32; 3]], o: &Options) -> [f32; 4] {
        let unit = |d: [f32; 3]| {
            let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if l > 0.0 && l.is_finite() { [d[0] / l, d[1] / l, d[2] / l] } else { [0.0, 0.0, 1.0] }
        };
        let units: Vec<[f32; 3]> = dirs.iter().map(|&d| unit(d)).collect();
        let sum = units.iter().fold([0.0; 3], |a, u| [a[0] + u[0], a[1] + u[1], a[2] + u[2]]);
        let c = unit(sum);
        // The angle the directions span: twice the largest angle from their centre.
        let spread = units
            .iter()
            .map(|u| 2.0 * (u[0] * c[0] + u[1] * c[1] + u[2] * c[2]).clamp(-1.0, 1.0).acos())
            .fold(0.0f32, f32::max);
        self.count_lookup();
        let texture = self.texture(id);
        let mut reader = Reader::new(self);
        let weight = o.weight();
        if texture.kind == MapKind::CubeFace {
            let fov_cot = texture.header.as_ref().and_then(|h| h.fov_cot).unwrap_or(1.0);
            let (face, fs, ft) = cube_face(c, fov_cot);
            let n = texture.levels[0].height.max(1) as f32 / 2.0;
            let inside = |v: f32| v.clamp(0.5 / n, 1.0 - 0.5 / n);
            let (col, row) = ((face / 2) as f32, (face % 2) as f32);
            let st = [(col + inside(fs)) / 3.0, (row + inside(ft)) / 2.0];
            let d = 0.5 * fov_cot * spread;
            let extent = [(d * o.width[0] + o.blur[0]) / 3.0, (d * o.width[1] + o.blur[1]) / 2.0];
            let extent = extent.map(|e| finite_or(e, 0.0));
            return lookup_weighted(texture, &mut reader, st, extent, [Wrap::Clamp; 2], weight);
        }
        let s = 0.5 + c[1].atan2(c[0]) / std::f32::consts::TAU;
        let t = c[2].clamp(-1.0, 1.0).acos() / std::f32::consts::PI;
        let sin = (1.0 - c[2] * c[2]).max(0.0).sqrt().max(1e-3);
        let ds = (spread / std::f32::consts::TAU / sin).min(1.0);
        let dt = spread / std::f32::consts::PI;
        let extent = [ds * o.width[0] + o.blur[0], dt * o.width[1] + o.blur[1]];
        let extent = extent.map(|e| finite_or(e, 0.0));
        lookup_weighted(texture, &mut reader, [s, t], extent, [Wrap::Periodic, Wrap::Clamp], weight)
    }

    /// `shadow()` of map `id` at the world-space points `points` (one, or four corners): the
    /// fraction of the filtered region in shadow. A map without matrices returns 0.
    pub fn shadow(&self, id: TextureId, points: &[[f32; 3]], o: &Options) -> f32 {
        let texture = self.texture(id);
        let Some(h) = texture.header.as_ref() else { return 0.0 };
        let (Some(screen), Some(camera)) = (h.world_to_screen, h.world_to_camera) else {
            return 0.0;
        };
        self.count_lookup();
        let row = |m: &[f32; 16], p: [f32; 3], c: usize| {
            p[0] * m[c] + p[1] * m[4 + c] + p[2] * m[8 + c] + m[12 + c]
        };
        let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
        let mut depth = 0.0;
        for &p in points {
            let w = row(&screen, p, 3);
            if !(w.is_finite() && w > 0.0) {
                return 0.0;
            }
            let st = [(row(&screen, p, 0) / w + 1.0) * 0.5, (1.0 - row(&screen, p, 1) / w) * 0.5];
            for k in 0..2 {
                lo[k] = lo[k].min(st[k]);
                hi[k] = hi[k].max(st[k]);
            }
            depth += row(&camera, p, 2) / points.len() as f32;
        }
        let level = texture.levels[0];
        let size = [level.width as f32, level.height as f32];
        let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
        let extent = [0, 1].map(|k| {
            let e = (hi[k] - lo[k]) * o.width[k] + o.blur[k].abs();
            finite_or(e, 0.0).max(1.0 / size[k])
        });
        if !(centre[0].is_finite() && centre[1].is_finite() && depth.is_finite()) {
            return 0.0;
        }
        let n = (o.samples.clamp(1, 4096) as f32).sqrt().ceil() as u32;
        let mut reader = Reader::new(self);
        let mut shadowed = 0u32;
        for j in 0..n {
            for i in 0..n {
                let h = jitter(centre, i, j);
                let fx = (i as f32 + h[0]) / n as f32 - 0.5;
                let fy = (j as f32 + h[1]) / n as f32 - 0.5;
                let s = centre[0] + fx * extent[0];
                let t = centre[1] + fy * extent[1];
                let (x, y) = ((s * size[0]).floor(), (t * size[1]).floor());
                if !(0.0..size[0]).contains(&x) || !(0.0..size[1]).contains(&y) {
                    continue;
                }
                let stored = reader.texel(texture, 0, x as u32, y as u32)[0];
                let bias = o.bias[0] + (o.bias[1] - o.bias[0]) * h[2];
                if depth - bias > stored {
                    shadowed += 1;
                }
            }
        }
        shadowed as f32 / (n * n) as f32
    }
}

/// The seed of the shadow samples' jitter.
const SHADOW_SEED: u64 = 0x5ad0_3a9b_11c4_d7e1;

/// Three numbers in [0, 1) from a hash of the lookup's centre and the stratum: the same
/// lookup always draws the same jitter.
fn jitter(centre: [f32; 2], i: u32, j: u32) -> [f32; 3] {
    let parts = [
        u64::from(centre[0].to_bits()),
        u64::from(centre[1].to_bits()),
        u64::from(i),
        u64::from(j),
    ];
    let a = reyes_sampling::hash(SHADOW_SEED, &parts);
    let unit = |v: u64| (v >> 40) as f32 / (1u64 << 24) as f32;
    [unit(a), unit(a << 24), unit(reyes_sampling::hash(SHADOW_SEED, &[a]))]
}

/// The face (`px nx py ny pz nz` = 0..6) of unit direction `d` and its face coordinates
/// (`s` right, `t` down, 0 to 1 across a face of cotangent `fov_cot`).
pub fn cube_face(d: [f32; 3], fov_cot: f32) -> (usize, f32, f32) {
    let [x, y, z] = d;
    let (ax, ay, az) = (x.abs(), y.abs(), z.abs());
    // (face, forward component, right component, up component)
    let (face, fwd, right, up) = if ax >= ay && ax >= az {
        if x >= 0.0 { (0, x, -z, y) } else { (1, -x, z, y) }
    } else if ay >= az {
        if y >= 0.0 { (2, y, x, -z) } else { (3, -y, x, z) }
    } else if z >= 0.0 {
        (4, z, x, y)
    } else {
        (5, -z, -x, y)
    };
    let fwd = fwd.max(1e-12);
    (face, 0.5 + 0.5 * fov_cot * right / fwd, 0.5 - 0.5 * fov_cot * up / fwd)
}

/// The direction through face coordinates `(s, t)` of `face` (the inverse of [`cube_face`]
/// for a 90-degree face), unnormalised.
pub fn cube_direction(face: usize, s: f32, t: f32) -> [f32; 3] {
    let (a, b) = (2.0 * s - 1.0, 1.0 - 2.0 * t);
    match face {
        0 => [1.0, b, -a],
        1 => [-1.0, b, a],
        2 => [a, 1.0, -b],
        3 => [a, -1.0, b],
        4 => [a, b, 1.0],
        _ => [-a, b, -1.0],
    }
}

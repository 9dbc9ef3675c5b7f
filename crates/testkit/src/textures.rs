//! The texture maps of the look-development scenes and tests, made by code so that they are
//! the same on every machine: `cargo xtask textures` writes them to `scenes/textures/`, and
//! a test checks that the committed files decode to exactly these pixels.
//!
//! Invariant: every texel is a pure function of its position (integer arithmetic and the
//! renderer's own gradient noise), so the maps never change unless this file does.

use image::{GrayImage, Luma, Rgb, RgbImage};
use reyes_texture::noise::fbm;

/// A `size` x `size` checkerboard of `check`-texel squares, `lo` and `hi` grey levels, the
/// square at the origin `hi`.
pub fn checker(size: u32, check: u32, lo: u8, hi: u8) -> GrayImage {
    GrayImage::from_fn(size, size, |x, y| {
        Luma([if (x / check + y / check).is_multiple_of(2) { hi } else { lo }])
    })
}

/// Wood: rings around an axis along t, warped by noise, in two browns (sRGB), 256 x 256,
/// periodic in s (the ring phase repeats) and in t (the noise is sampled on a torus).
pub fn wood() -> RgbImage {
    let n = 256u32;
    RgbImage::from_fn(n, n, |x, y| {
        let (s, t) = (x as f32 / n as f32, y as f32 / n as f32);
        let tau = std::f32::consts::TAU;
        // Noise on a circle in each direction, so the map tiles.
        let p = [2.0 * (tau * s).cos(), 2.0 * (tau * s).sin(), 3.0 * (tau * t).cos()];
        let q = [3.0 * (tau * t).sin(), p[0] + 7.1, p[1] - 3.3];
        let warp = 0.12 * fbm(p, 3) + 0.06 * fbm(q, 2);
        let rings = (8.0 * s + warp).fract();
        let grain = 0.5 + 0.5 * (0.8 * fbm([64.0 * s, 2.0 * t, 0.5], 2)).clamp(-1.0, 1.0);
        let k = (rings * rings * (3.0 - 2.0 * rings)) * 0.8 + 0.2 * grain;
        let light = [200.0, 150.0, 95.0];
        let dark = [120.0, 70.0, 35.0];
        let c = |i: usize| (dark[i] + (light[i] - dark[i]) * k).round().clamp(0.0, 255.0) as u8;
        Rgb([c(0), c(1), c(2)])
    })
}

/// A height map of rounded tiles: 4 x 4 tiles over 256 x 256 texels, each a cushion rising
/// from 0 in its grout lines to 255 at its middle (linear data), periodic.
pub fn tiles() -> GrayImage {
    let n = 256u32;
    let tile = n / 4;
    GrayImage::from_fn(n, n, |x, y| {
        let edge = |v: u32| {
            let d = (v % tile).min(tile - 1 - v % tile) as f32 / (tile as f32 / 2.0);
            (d * 4.0).min(1.0)
        };
        let h = edge(x) * edge(y);
        Luma([(255.0 * h * h * (3.0 - 2.0 * h)).round() as u8])
    })
}

/// Every map of `scenes/textures/`, by file name.
pub fn scene_maps() -> Vec<(&'static str, image::DynamicImage)> {
    vec![
        ("checker.png", checker(64, 8, 40, 215).into()),
        ("wood.png", wood().into()),
        ("tiles.png", tiles().into()),
    ]
}

//! MIP pyramids: level `k + 1` is the 2 x 2 box average of level `k`, down to 1 x 1.
//!
//! Invariants: level `k + 1` has `ceil(w / 2) x ceil(h / 2)` texels; texel `(x, y)` of it
//! averages texels `(2x, 2y) .. (2x + 1, 2y + 1)` of level `k`, a column or row past an odd
//! edge replaced by the edge's own (so a constant image stays constant at every level, and
//! a power-of-two image keeps its mean exactly up to rounding).

use crate::TILE;
use crate::load::Image;

/// One level of a pyramid in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct MipLevel {
    /// Texels across.
    pub width: u32,
    /// Texels down.
    pub height: u32,
    /// RGBA, row by row.
    pub texels: Vec<f32>,
}

impl MipLevel {
    /// The RGBA texel at `(x, y)` (in range).
    fn at(&self, x: u32, y: u32) -> [f32; 4] {
        let k = 4 * (y as usize * self.width as usize + x as usize);
        [self.texels[k], self.texels[k + 1], self.texels[k + 2], self.texels[k + 3]]
    }

    /// The next smaller level.
    fn half(&self) -> MipLevel {
        let (w, h) = (self.width.div_ceil(2), self.height.div_ceil(2));
        let mut texels = Vec::with_capacity(4 * w as usize * h as usize);
        for y in 0..h {
            let (y0, y1) = (2 * y, (2 * y + 1).min(self.height - 1));
            for x in 0..w {
                let (x0, x1) = (2 * x, (2 * x + 1).min(self.width - 1));
                let q = [self.at(x0, y0), self.at(x1, y0), self.at(x0, y1), self.at(x1, y1)];
                let [a, b, c, d] = q;
                for k in 0..4 {
                    texels.push(0.25 * ((a[k] + b[k]) + (c[k] + d[k])));
                }
            }
        }
        MipLevel { width: w, height: h, texels }
    }

    /// Tile `(tx, ty)` as little-endian `f32` RGBA, [`TILE`] x [`TILE`] texels row by row;
    /// texels past the level's edge are 0.
    pub fn tile_bytes(&self, tx: u32, ty: u32, out: &mut [u8]) {
        out.fill(0);
        for row in 0..TILE as u32 {
            let y = ty * TILE as u32 + row;
            if y >= self.height {
                break;
            }
            for col in 0..TILE as u32 {
                let x = tx * TILE as u32 + col;
                if x >= self.width {
                    break;
                }
                let px = self.at(x, y);
                let k = 16 * (row as usize * TILE + col as usize);
                for (c, v) in px.iter().enumerate() {
                    out[k + 4 * c..k + 4 * c + 4].copy_from_slice(&v.to_le_bytes());
                }
            }
        }
    }
}

/// A whole pyramid, finest level first.
#[derive(Debug, Clone, PartialEq)]
pub struct Pyramid {
    /// Level 0 (the image) down to 1 x 1.
    pub levels: Vec<MipLevel>,
}

impl Pyramid {
    /// The pyramid of `image`.
    pub fn build(image: Image) -> Pyramid {
        let mut levels =
            vec![MipLevel { width: image.width, height: image.height, texels: image.texels }];
        while let Some(last) = levels.last()
            && (last.width > 1 || last.height > 1)
        {
            let next = last.half();
            levels.push(next);
        }
        Pyramid { levels }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_and_keep_the_mean() {
        let (w, h) = (8u32, 4u32);
        let texels: Vec<f32> = (0..w * h).flat_map(|k| [k as f32, 1.0, 0.0, 1.0]).collect();
        let mean = (0..w * h).map(|k| k as f32).sum::<f32>() / (w * h) as f32;
        let p = Pyramid::build(Image { width: w, height: h, texels });
        let sizes: Vec<(u32, u32)> = p.levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(8, 4), (4, 2), (2, 1), (1, 1)]);
        let top = p.levels[3].at(0, 0);
        assert!((top[0] - mean).abs() < 1e-4 && top[1] == 1.0, "{top:?} vs {mean}");
    }

    #[test]
    fn odd_sizes_reach_one_texel_and_constants_stay_constant() {
        let texels = [0.3f32, 0.6, 0.9, 1.0].repeat(5 * 3);
        let p = Pyramid::build(Image { width: 5, height: 3, texels });
        let sizes: Vec<(u32, u32)> = p.levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(5, 3), (3, 2), (2, 1), (1, 1)]);
        for l in &p.levels {
            for px in l.texels.chunks_exact(4) {
                assert_eq!(px, [0.3, 0.6, 0.9, 1.0]);
            }
        }
    }
}

//! The sample patterns of the study: the hider's own samples of each pattern, their
//! periodograms, and a point-sampled zone plate.
//!
//! Everything here goes through the real hider: sample positions come from
//! [`Hider::bucket_samples`] with the same bucket layout as a render.

use rayon::prelude::*;
use reyes_hider::{Frame, Hider, HiderConfig, Pairing, Pattern};

/// A sample pattern of the study: each spatial pattern the hider offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sampler {
    /// FIG. 3: the regular grid (`jitter: false`; times and lens at their strata's centres).
    Regular,
    /// Uniform random positions, no stratification.
    Random,
    /// FIG. 5: one jittered pattern repeated in every pixel.
    Fig5,
    /// FIG. 6: a new jittered point in each stratum of every pixel (Appendix A, the default).
    Fig6,
    /// FIG. 7: FIG. 5's reference points plus a bounded random offset.
    Fig7,
    /// Owen-scrambled Sobol (0,2) per pixel.
    Sobol,
    /// One Owen-scrambled Sobol sequence over position, time and lens, with correlated
    /// multi-jittered offsets within each stratum.
    SobolJoint,
}

impl Sampler {
    /// Every sampler, in the order of the figures.
    pub const ALL: [Sampler; 7] = [
        Sampler::Regular,
        Sampler::Random,
        Sampler::Fig5,
        Sampler::Fig6,
        Sampler::Fig7,
        Sampler::Sobol,
        Sampler::SobolJoint,
    ];

    /// Name for legends.
    pub fn label(self) -> &'static str {
        match self {
            Sampler::Regular => "regular (FIG. 3)",
            Sampler::Random => "random",
            Sampler::Fig5 => "FIG. 5",
            Sampler::Fig6 => "FIG. 6 (App. A)",
            Sampler::Fig7 => "FIG. 7",
            Sampler::Sobol => "Owen-Sobol (0,2)",
            Sampler::SobolJoint => "joint Sobol + CMJ",
        }
    }

    /// The hider's pattern.
    pub fn pattern(self) -> Pattern {
        match self {
            Sampler::Regular => Pattern::Regular,
            Sampler::Random => Pattern::Random,
            Sampler::Fig5 => Pattern::Fig5,
            Sampler::Fig6 => Pattern::Fig6,
            Sampler::Fig7 => Pattern::Fig7,
            Sampler::Sobol => Pattern::Sobol,
            Sampler::SobolJoint => Pattern::SobolJoint,
        }
    }

    /// The scene-file fields of `hider` that select it.
    pub fn scene_fields(self) -> &'static str {
        match self {
            Sampler::Regular => "jitter: false",
            Sampler::Random => "jitter: true, pattern: Random",
            Sampler::Fig5 => "jitter: true, pattern: Fig5",
            Sampler::Fig6 => "jitter: true, pattern: Fig6",
            Sampler::Fig7 => "jitter: true, pattern: Fig7",
            Sampler::Sobol => "jitter: true, pattern: Sobol",
            Sampler::SobolJoint => "jitter: true, pattern: SobolJoint",
        }
    }
}

/// One sample, in raster coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Raster x.
    pub x: f32,
    /// Raster y (down).
    pub y: f32,
    /// Shutter time in [0, 1).
    pub t: f32,
    /// Lens x (unit disk).
    pub lx: f32,
    /// Lens y.
    pub ly: f32,
}

/// Bucket size used by the study (the scene default).
const BUCKET: u32 = 16;

/// The samples of every pixel of a `width` x `height` image, as the hider makes them for a
/// render with 16 x 16 buckets: sample `s` of pixel `(x, y)` at `(y*width + x)*NS + s`.
pub fn samples(
    sampler: Sampler,
    nx: u32,
    ny: u32,
    width: u32,
    height: u32,
    seed: u64,
    pairing: Pairing,
) -> Vec<Sample> {
    let cfg = HiderConfig {
        nx,
        ny,
        pattern: sampler.pattern(),
        time_pairing: pairing,
        seed,
        ..HiderConfig::default()
    };
    let frame = Frame::new(width, height, 0, BUCKET, BUCKET);
    let hider = Hider::new(cfg, frame);
    let ns = hider.ns();
    let mut out = vec![Sample::default(); (width * height) as usize * ns];
    for b in 0..frame.bucket_count() {
        let (left, top) = frame.bucket_origin(b);
        let bs = hider.bucket_samples(b);
        for pixel in 0..frame.pixels_per_bucket() {
            let gx = left + (pixel as u32 % frame.bucket_w) as i32;
            let gy = top + (pixel as u32 / frame.bucket_w) as i32;
            if gx < 0 || gy < 0 || gx >= width as i32 || gy >= height as i32 {
                continue;
            }
            for s in 0..ns {
                let k = pixel * ns + s;
                out[(gy as usize * width as usize + gx as usize) * ns + s] = Sample {
                    x: left as f32 + bs.x[k],
                    y: top as f32 + bs.y[k],
                    t: bs.t[k],
                    lx: bs.lx[k],
                    ly: bs.ly[k],
                };
            }
        }
    }
    out
}

/// A periodogram on the frequency grid `k = (i, j) * step` cycles per pixel,
/// `i, j in -half..=half`.
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Grid half-size.
    pub half: usize,
    /// Frequency step, cycles per pixel.
    pub step: f64,
    /// Power at `(i, j)`: index `(j + half) * (2 half + 1) + (i + half)`.
    pub power: Vec<f64>,
}

impl Spectrum {
    /// Side of the grid.
    pub fn side(&self) -> usize {
        2 * self.half + 1
    }

    /// Mean power over the frequencies with `lo < |k| <= hi` (cycles per pixel).
    pub fn band(&self, lo: f64, hi: f64) -> f64 {
        let n = self.side();
        let (mut sum, mut count) = (0.0, 0usize);
        for j in 0..n {
            for i in 0..n {
                let (fi, fj) = (i as f64 - self.half as f64, j as f64 - self.half as f64);
                let r = (fi * fi + fj * fj).sqrt() * self.step;
                if r > lo && r <= hi {
                    sum += self.power[j * n + i];
                    count += 1;
                }
            }
        }
        sum / count.max(1) as f64
    }

    /// Power averaged over rings of width `step`, from 0 to `half * step`: (|k|, power).
    /// The zero-frequency bin is left out.
    pub fn radial(&self) -> Vec<(f64, f64)> {
        let n = self.side();
        let mut sum = vec![0.0; self.half + 1];
        let mut count = vec![0usize; self.half + 1];
        for j in 0..n {
            for i in 0..n {
                let (fi, fj) = (i as f64 - self.half as f64, j as f64 - self.half as f64);
                let r = (fi * fi + fj * fj).sqrt().round() as usize;
                if r == 0 || r > self.half {
                    continue;
                }
                sum[r] += self.power[j * n + i];
                count[r] += 1;
            }
        }
        (1..=self.half)
            .filter(|&r| count[r] > 0)
            .map(|r| (r as f64 * self.step, sum[r] / count[r] as f64))
            .collect()
    }
}

/// Periodogram of a point set: `|sum_p exp(-2 pi i k . p)|^2 / N` on the grid of
/// [`Spectrum`], by a direct sum (separable in x and y).
pub fn periodogram(points: &[[f64; 2]], half: usize, step: f64) -> Vec<f64> {
    let n = 2 * half + 1;
    let mut re = vec![0.0f64; n * n];
    let mut im = vec![0.0f64; n * n];
    let mut ex = vec![(0.0f64, 0.0f64); n];
    let mut ey = vec![(0.0f64, 0.0f64); n];
    let tau = std::f64::consts::TAU;
    for p in points {
        for i in 0..n {
            let k = (i as f64 - half as f64) * step;
            let (s, c) = (-tau * k * p[0]).sin_cos();
            ex[i] = (c, s);
            let (s, c) = (-tau * k * p[1]).sin_cos();
            ey[i] = (c, s);
        }
        for j in 0..n {
            let (yc, ys) = ey[j];
            let row_re = &mut re[j * n..(j + 1) * n];
            let row_im = &mut im[j * n..(j + 1) * n];
            for i in 0..n {
                let (xc, xs) = ex[i];
                row_re[i] += xc * yc - xs * ys;
                row_im[i] += xc * ys + xs * yc;
            }
        }
    }
    let inv = 1.0 / points.len().max(1) as f64;
    re.iter().zip(&im).map(|(a, b)| (a * a + b * b) * inv).collect()
}

/// The periodogram of `sampler`'s sample positions with `n x n` samples per pixel, averaged
/// over `windows` windows of `window x window` pixels (tiling an image from its top-left
/// corner, so windows fall at different places in the buckets).
pub fn mean_periodogram(
    sampler: Sampler,
    n: u32,
    window: u32,
    windows: u32,
    half: usize,
    step: f64,
    seed: u64,
) -> Spectrum {
    let across = (windows as f64).sqrt().ceil() as u32;
    let size = across * window;
    let all = samples(sampler, n, n, size, size, seed, Pairing::Decorrelated);
    let ns = (n * n) as usize;
    let side = 2 * half + 1;
    let sums: Vec<Vec<f64>> = (0..windows)
        .into_par_iter()
        .map(|w| {
            let (wx, wy) = ((w % across) * window, (w / across) * window);
            let mut pts = Vec::with_capacity((window * window) as usize * ns);
            for y in wy..wy + window {
                for x in wx..wx + window {
                    let base = (y * size + x) as usize * ns;
                    for smp in &all[base..base + ns] {
                        pts.push([(smp.x - wx as f32) as f64, (smp.y - wy as f32) as f64]);
                    }
                }
            }
            periodogram(&pts, half, step)
        })
        .collect();
    let mut power = vec![0.0; side * side];
    for s in &sums {
        for (p, v) in power.iter_mut().zip(s) {
            *p += v / windows as f64;
        }
    }
    Spectrum { half, step, power }
}

/// The zone plate `0.5 + 0.5 cos(pi f r^2 / R)` with `r` the distance from the image centre
/// and `R = size / 2`: its local frequency `f r / R` cycles per pixel grows linearly from the
/// centre to `f` at the middle of each side.
pub fn zone_plate_value(x: f64, y: f64, size: u32, f: f64) -> f64 {
    let c = size as f64 / 2.0;
    let r2 = (x - c).powi(2) + (y - c).powi(2);
    0.5 + 0.5 * (std::f64::consts::PI * f * r2 / c).cos()
}

/// The zone plate point-sampled at `sampler`'s positions (`n x n` per pixel) and filtered by a
/// one-pixel box (each pixel the mean of its samples), as the hider would see a surface whose
/// colour is the zone-plate function. Row-major `size x size`.
pub fn zone_plate(sampler: Sampler, n: u32, size: u32, f: f64, seed: u64) -> Vec<f32> {
    let all = samples(sampler, n, n, size, size, seed, Pairing::Decorrelated);
    let ns = (n * n) as usize;
    all.chunks(ns)
        .map(|px| {
            (px.iter().map(|s| zone_plate_value(s.x as f64, s.y as f64, size, f)).sum::<f64>()
                / ns as f64) as f32
        })
        .collect()
}

/// The zone plate box-filtered by a 32 x 32 midpoint rule per pixel (the reference).
pub fn zone_plate_reference(size: u32, f: f64) -> Vec<f32> {
    let m = 32;
    (0..size * size)
        .into_par_iter()
        .map(|p| {
            let (x, y) = ((p % size) as f64, (p / size) as f64);
            let mut sum = 0.0;
            for j in 0..m {
                for i in 0..m {
                    let (u, v) = ((i as f64 + 0.5) / m as f64, (j as f64 + 0.5) / m as f64);
                    sum += zone_plate_value(x + u, y + v, size, f);
                }
            }
            (sum / (m * m) as f64) as f32
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodogram_of_a_regular_grid_has_spikes_at_the_sampling_rate() {
        let s = mean_periodogram(Sampler::Regular, 2, 4, 4, 16, 0.25, 1);
        let side = s.side();
        let at = |i: i64, j: i64| {
            s.power[(j + s.half as i64) as usize * side + (i + s.half as i64) as usize]
        };
        // 2 samples per pixel: spikes at multiples of 2 cycles per pixel (index 8), N high.
        let n = (4 * 4 * 4) as f64;
        assert!((at(8, 0) - n).abs() < 1e-6 * n && (at(8, 8) - n).abs() < 1e-6 * n);
        assert!(at(3, 0) < 1e-6 && at(5, 1) < 1e-6);
        // Jittered: no spikes off zero, and little power at low frequency.
        let j = mean_periodogram(Sampler::Fig6, 2, 4, 16, 16, 0.25, 1);
        assert!(j.power.iter().enumerate().all(|(k, &p)| k == j.power.len() / 2 || p < 8.0));
    }
}

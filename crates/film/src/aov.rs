//! AOV pixels (stage: film, per bucket then per frame): each AOV's per-sample values become
//! pixels through its filter ([`AovFilter`]), in a bordered window per bucket that is summed
//! into the frame's [`AovFilm`] in bucket order, as the beauty's windows are.
//!
//! Invariants: `Filter` channels are the beauty's splat of the same samples with the same
//! weights (every sample counts, a sample with no visible surface with the AOV's background
//! value), summed in `f64` and rounded once; the pixel-own filters (`Min`, `Max`, `Zmin`,
//! `Nearest`) write only the bucket's own pixels and leave the border 0, so the sum over
//! windows is the chosen sample's value exactly (adding zeros), and ids stay exact integers.

use reyes_scene::AovFilter;

use crate::FilterTable;

/// One AOV's place among the per-sample channels and its filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AovChannels {
    /// First channel.
    pub start: usize,
    /// Channels.
    pub len: usize,
    /// How the samples become a pixel.
    pub filter: AovFilter,
}

/// The AOV values of one bucket's window (the bucket grown by the filter's border).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AovWindow {
    /// Raster x of the left column.
    pub x0: i32,
    /// Raster y of the top row.
    pub y0: i32,
    /// Width in pixels.
    pub w: u32,
    /// Height in pixels.
    pub h: u32,
    /// Channels per pixel.
    pub channels: usize,
    /// `[(y * w + x) * channels + c]`.
    pub data: Vec<f32>,
}

/// What one bucket hands the AOV splat: its per-sample values, laid out
/// `[(pixel * NS + s) * channels + c]`, each sample's front depth, and each sample's
/// bucket-local position (`x[pixel * NS + s]`, `y[...]`, as the values).
#[derive(Debug, Clone, Copy)]
pub struct AovSamples<'a> {
    /// Channels per sample.
    pub channels: usize,
    /// The values.
    pub values: &'a [f32],
    /// Front depth per sample (`+inf`: nothing visible).
    pub front_z: &'a [f32],
    /// Sample x, bucket-local.
    pub x: &'a [f32],
    /// Sample y, bucket-local.
    pub y: &'a [f32],
}

/// Filter one bucket's AOV samples into `out` (see the module invariants). The bucket is
/// `bw x bh` pixels with its top-left pixel at raster `(left, top)`.
#[allow(clippy::too_many_arguments)] // mirrors the beauty's splat
pub fn splat_aovs(
    table: &FilterTable,
    (left, top): (i32, i32),
    (bw, bh): (u32, u32),
    aovs: &[AovChannels],
    s: &AovSamples,
    out: &mut AovWindow,
) {
    let ns = table.ns();
    let b = table.border() as usize;
    let fw = table.footprint() as usize;
    let (bwu, bhu) = (bw as usize, bh as usize);
    let (ww, wh) = (bwu + 2 * b, bhu + 2 * b);
    let ch = s.channels;
    let p_count = bwu * bhu;
    assert_eq!(s.values.len(), p_count * ns * ch, "splat_aovs: wrong number of values");
    out.x0 = left.saturating_sub(b as i32);
    out.y0 = top.saturating_sub(b as i32);
    out.w = ww as u32;
    out.h = wh as u32;
    out.channels = ch;
    out.data.clear();
    out.data.resize(ww * wh * ch, 0.0);
    let value = |pixel: usize, s_index: usize, c: usize| s.values[(pixel * ns + s_index) * ch + c];

    // Pixel-own filters: the bucket's own pixels.
    for y in 0..bhu {
        for x in 0..bwu {
            let pixel = y * bwu + x;
            let dst = ((y + b) * ww + x + b) * ch;
            for a in aovs {
                let chosen = match a.filter {
                    AovFilter::Filter => continue,
                    AovFilter::Min | AovFilter::Max | AovFilter::Average => None,
                    AovFilter::Zmin => Some(pick(ns, |k| s.front_z[pixel * ns + k])),
                    AovFilter::Nearest => Some(pick(ns, |k| {
                        let i = pixel * ns + k;
                        let (dx, dy) = (s.x[i] - (x as f32 + 0.5), s.y[i] - (y as f32 + 0.5));
                        dx * dx + dy * dy
                    })),
                };
                for c in a.start..a.start + a.len {
                    out.data[dst + c] = match (chosen, a.filter) {
                        (Some(k), _) => value(pixel, k, c),
                        (None, AovFilter::Min) => {
                            (0..ns).map(|k| value(pixel, k, c)).fold(f32::INFINITY, f32::min)
                        }
                        (None, AovFilter::Average) => {
                            let sum: f64 = (0..ns).map(|k| f64::from(value(pixel, k, c))).sum();
                            (sum / ns as f64) as f32
                        }
                        (None, _) => {
                            (0..ns).map(|k| value(pixel, k, c)).fold(f32::NEG_INFINITY, f32::max)
                        }
                    };
                }
            }
        }
    }

    // The beauty's filter: each window pixel gathers exactly the terms the scatter adds.
    let filtered: Vec<usize> = aovs
        .iter()
        .filter(|a| a.filter == AovFilter::Filter)
        .flat_map(|a| a.start..a.start + a.len)
        .collect();
    if filtered.is_empty() || p_count == 0 {
        return;
    }
    let weights = table.weights();
    let per_sample = fw * fw;
    let mut acc = vec![0.0_f64; filtered.len()];
    for wy in 0..wh {
        let (j_lo, j_hi) = (wy.saturating_sub(bhu - 1), wy.min(fw - 1));
        for wx in 0..ww {
            let (i_lo, i_hi) = (wx.saturating_sub(bwu - 1), wx.min(fw - 1));
            acc.fill(0.0);
            for j in j_lo..=j_hi {
                for i in i_lo..=i_hi {
                    let pixel = (wy - j) * bwu + (wx - i);
                    let tap = j * fw + i;
                    for k in 0..ns {
                        let w = weights[k * per_sample + tap];
                        if w == 0.0 {
                            continue; // adds exactly nothing
                        }
                        let f = f64::from(w);
                        let base = (pixel * ns + k) * ch;
                        for (a, &c) in acc.iter_mut().zip(&filtered) {
                            *a += f * f64::from(s.values[base + c]);
                        }
                    }
                }
            }
            let dst = (wy * ww + wx) * ch;
            for (a, &c) in acc.iter().zip(&filtered) {
                out.data[dst + c] = *a as f32;
            }
        }
    }
}

/// The index in `0..n` whose key is smallest (NaN last; ties to the lower index).
fn pick(n: usize, key: impl Fn(usize) -> f32) -> usize {
    let mut best = 0;
    let mut best_key = key(0);
    for k in 1..n {
        let v = key(k);
        if v < best_key || (best_key.is_nan() && !v.is_nan()) {
            best = k;
            best_key = v;
        }
    }
    best
}

/// The frame's AOV pixels: the sum of every bucket's [`AovWindow`].
#[derive(Debug, Clone, PartialEq)]
pub struct AovFilm {
    width: u32,
    height: u32,
    channels: usize,
    data: Vec<f32>,
}

impl AovFilm {
    /// A `width x height` image of `channels` channels, all 0.
    pub fn new(width: u32, height: u32, channels: usize) -> AovFilm {
        AovFilm {
            width,
            height,
            channels,
            data: vec![0.0; width as usize * height as usize * channels],
        }
    }

    /// Add one window (cropped to the image). Call in bucket order.
    pub fn add(&mut self, win: &AovWindow) {
        assert_eq!(win.channels, self.channels, "AovFilm::add: channel count differs");
        let ch = self.channels;
        for ly in 0..win.h as i64 {
            let y = i64::from(win.y0) + ly;
            if y < 0 || y >= i64::from(self.height) {
                continue;
            }
            for lx in 0..win.w as i64 {
                let x = i64::from(win.x0) + lx;
                if x < 0 || x >= i64::from(self.width) {
                    continue;
                }
                let src = ((ly * i64::from(win.w) + lx) as usize) * ch;
                let dst = (y as usize * self.width as usize + x as usize) * ch;
                for c in 0..ch {
                    self.data[dst + c] += win.data[src + c];
                }
            }
        }
    }

    /// The pixels `[x0, x1) x [y0, y1)` (`rect = [x0, x1, y0, y1]`, within the image) as an
    /// image of their own.
    pub fn crop(&self, [x0, x1, y0, y1]: [u32; 4]) -> AovFilm {
        let ch = self.channels;
        let mut data = Vec::with_capacity((x1 - x0) as usize * (y1 - y0) as usize * ch);
        for y in y0..y1 {
            let row = y as usize * self.width as usize;
            data.extend_from_slice(&self.data[(row + x0 as usize) * ch..(row + x1 as usize) * ch]);
        }
        AovFilm { width: x1 - x0, height: y1 - y0, channels: ch, data }
    }

    /// Channels per pixel.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Channel `c` of pixel `(x, y)`.
    pub fn value(&self, x: u32, y: u32, c: usize) -> f32 {
        self.data[(y as usize * self.width as usize + x as usize) * self.channels + c]
    }

    /// All values, `[(y * width + x) * channels + c]`.
    pub fn data(&self) -> &[f32] {
        &self.data
    }
}

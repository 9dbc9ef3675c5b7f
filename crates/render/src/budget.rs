//! The memory budget: what a frame is estimated to need before it starts, what is left of
//! the limit for micropolygons, and the default limit.
//!
//! The estimate counts the allocations whose size follows from the settings alone: the film,
//! its encoded copy, every worker's per-sample arrays and filter window, and a row of bucket
//! windows waiting to be merged. A scene whose estimate exceeds the limit is refused before
//! anything is allocated. What remains of the limit bounds the micropolygons the dicer may
//! hold at once ([`reyes_dice::DiceOptions::max_micropolygons`]), checked as each grid is
//! planned by the split walk, before any of a patch's grids is diced and shaded; ray trees are bounded separately, by their own ray budget.

use reyes_dice::MICROPOLYGON_BYTES;
use reyes_scene::Scene;

use crate::settings::frame_for;

/// Bytes per sample of a worker's bucket arrays: position, time, lens position and their
/// permutations, the visible-point list head, its first visible point, the sample's colour
/// and depth (each array of the hider's scratch, rounded up).
pub const SAMPLE_BYTES: u64 = 128;
/// Bytes per visible point kept in a bucket (the point and its list link, rounded up).
pub const VISIBLE_POINT_BYTES: u64 = 128;
/// Bytes per pixel of the film (RGBA and Z as `f32`).
pub const FILM_PIXEL_BYTES: u64 = 20;
/// Bytes per pixel of the encoded output's planes and conversion buffers.
pub const OUTPUT_PIXEL_BYTES: u64 = 24;
/// Bytes the budget keeps for the program itself, its threads and the scene.
pub const BASE_BYTES: u64 = 64 << 20;

/// What a frame is estimated to need, in bytes, by part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Estimate {
    /// The film and its encoded copy.
    pub film: u64,
    /// Every worker's per-sample arrays and window, and one row of windows.
    pub buckets: u64,
    /// The program, its threads and the scene.
    pub base: u64,
}

impl Estimate {
    /// `scene` rendered with `threads` workers.
    pub fn new(scene: &Scene, threads: usize) -> Estimate {
        let frame = frame_for(scene);
        let pixels = u64::from(scene.image.width) * u64::from(scene.image.height);
        let (sx, sy) = scene.hider.pixel_samples;
        let spp = u64::from(sx) * u64::from(sy);
        let bucket_px = u64::from(frame.bucket_w) * u64::from(frame.bucket_h);
        let reach = 2 * u64::from(frame.border);
        let window_px = (u64::from(frame.bucket_w) + reach) * (u64::from(frame.bucket_h) + reach);
        let worker = bucket_px
            .saturating_mul(spp)
            .saturating_mul(SAMPLE_BYTES)
            .saturating_add(window_px * FILM_PIXEL_BYTES);
        let row = u64::from(frame.buckets_x).saturating_mul(window_px * FILM_PIXEL_BYTES);
        Estimate {
            film: pixels.saturating_mul(FILM_PIXEL_BYTES + OUTPUT_PIXEL_BYTES),
            buckets: worker.saturating_mul(threads.max(1) as u64).saturating_add(row),
            base: BASE_BYTES,
        }
    }

    /// The whole estimate.
    pub fn total(&self) -> u64 {
        self.film.saturating_add(self.buckets).saturating_add(self.base)
    }

    /// The micropolygons that fit in three quarters of what `limit` leaves over (a limit
    /// below the estimate is refused before this is asked).
    pub fn micropolygons_left(&self, limit: u64) -> u64 {
        limit.saturating_sub(self.total()) / 4 * 3 / MICROPOLYGON_BYTES
    }

    /// The visible points one of `threads` workers may keep in a bucket: its share of the
    /// last quarter of what `limit` leaves over.
    pub fn points_left(&self, limit: u64, threads: usize) -> u64 {
        limit.saturating_sub(self.total()) / 4 / threads.max(1) as u64 / VISIBLE_POINT_BYTES
    }
}

/// The default memory limit: three quarters of the smaller of the machine's memory and the
/// process's address-space limit (`ulimit -v`, `prlimit --as`), or `None` where neither can
/// be read.
pub fn default_memory_limit() -> Option<u64> {
    let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| mem_total(&s));
    let cap = std::fs::read_to_string("/proc/self/limits").ok().and_then(|s| address_limit(&s));
    let least = match (total, cap) {
        (Some(a), Some(b)) => a.min(b),
        (a, b) => a.or(b)?,
    };
    Some(least / 4 * 3)
}

/// `MemTotal` of `/proc/meminfo`, in bytes.
fn mem_total(meminfo: &str) -> Option<u64> {
    let line = meminfo.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

/// The soft "Max address space" of `/proc/self/limits`, in bytes (`None` if unlimited).
fn address_limit(limits: &str) -> Option<u64> {
    let line = limits.lines().find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..].split_whitespace().next()?.parse().ok()
}

/// Parse a memory size: bytes, or a number with `K`, `M`, `G` or `T` (powers of 1024,
/// optionally followed by `B` or `iB`), e.g. `1.5G`, `512M`, `2GiB`.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let digits = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (number, unit) = t.split_at(digits);
    let value: f64 = number.parse().map_err(|_| format!("not a memory size: `{text}`"))?;
    let shift = match unit.trim().trim_end_matches("iB").trim_end_matches('B') {
        "" => 0,
        "K" | "k" => 10,
        "M" | "m" => 20,
        "G" | "g" => 30,
        "T" | "t" => 40,
        _ => return Err(format!("unknown unit in memory size `{text}` (use K, M, G or T)")),
    };
    let bytes = value * (1u64 << shift) as f64;
    if !(bytes.is_finite() && (1.0..1.8e19).contains(&bytes)) {
        return Err(format!("memory size out of range: `{text}`"));
    }
    Ok(bytes as u64)
}

/// Megabytes, rounded up, for messages.
pub fn mb(bytes: u64) -> u64 {
    bytes.div_ceil(1 << 20)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_in_powers_of_1024() {
        assert_eq!(parse_size("1024"), Ok(1024));
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("1.5G"), Ok(3 << 29));
        assert_eq!(parse_size("2GiB"), Ok(2 << 30));
        assert_eq!(parse_size("4 GB"), Ok(4 << 30));
        assert!(parse_size("").is_err());
        assert!(parse_size("0").is_err());
        assert!(parse_size("12X").is_err());
        assert!(parse_size("-1G").is_err());
        assert!(parse_size("1e30").is_err());
    }

    #[test]
    fn proc_files_are_read() {
        assert_eq!(
            mem_total("MemTotal:       24576000 kB\nMemFree: 1 kB\n"),
            Some(24576000 * 1024)
        );
        let limits = "Limit                     Soft Limit           Hard Limit           Units\n\
                      Max address space         2000000000           unlimited            bytes\n";
        assert_eq!(address_limit(limits), Some(2_000_000_000));
        let open = "Max address space         unlimited            unlimited            bytes\n";
        assert_eq!(address_limit(open), None);
    }

    #[test]
    fn the_estimate_follows_image_samples_and_buckets() {
        use reyes_testkit::fixtures;
        let camera = fixtures::camera([0.0, 0.0, -5.0], [0.0; 3], 40.0, None);
        let mut scene = fixtures::scene(640, 480, camera, vec![]);
        scene.hider.pixel_samples = (4, 4);
        let e = Estimate::new(&scene, 2);
        assert_eq!(e.film, 640 * 480 * 44);
        // 16x16 buckets with a 1-pixel border (Gaussian of width 2): 18x18 windows.
        let worker = 256 * 16 * SAMPLE_BYTES + 18 * 18 * FILM_PIXEL_BYTES;
        let across = u64::from(frame_for(&scene).buckets_x);
        assert_eq!(e.buckets, 2 * worker + across * 18 * 18 * FILM_PIXEL_BYTES);
        // A 1024-pixel bucket of 64x64 samples needs more than half a terabyte per worker.
        scene.hider.pixel_samples = (64, 64);
        scene.hider.bucket_size = (1024, 1024);
        assert!(Estimate::new(&scene, 1).buckets > 500 << 30);
    }
}

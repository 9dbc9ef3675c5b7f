//! Which buckets a render draws, what each hands the film, and the assembly of bucket results
//! into the frame: the pieces behind crop windows, tiles, checkpoints and their merge.
//!
//! Invariant (exact reassembly): a pixel's value is the `f32` sum, in bucket raster order, of
//! the windows that cover it ([`reyes_film::Film::add`], 0 + w₁ + w₂ + …). A bucket's result
//! depends only on the scene and the bucket index, so any split of the buckets into tiles,
//! or into buckets rendered now and buckets read back from a checkpoint, reassembles into
//! the same bits as long as [`assemble`] is given every bucket's result in raster order:
//! the results are kept whole (window and border), never pre-summed across buckets.

use reyes_film::{AovFilm, AovWindow, Film, Window};
use reyes_hider::Frame;
use reyes_scene::Scene;

/// What one bucket adds to the frame.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BucketResult {
    /// The beauty's window (None: the bucket drew nothing, and adds nothing).
    pub window: Option<Window>,
    /// The AOVs' window, when the scene has AOVs (an empty bucket still has one: the AOVs'
    /// background values).
    pub aov: Option<AovWindow>,
}

/// The buckets of `frame` whose windows (the bucket and the filter's border) meet the pixels
/// `scene.image.crop` selects, in raster order: every bucket without a crop window.
pub fn scene_buckets(scene: &Scene, frame: &Frame) -> Vec<usize> {
    let all = 0..frame.bucket_count();
    if scene.image.crop.is_none() {
        return all.collect();
    }
    let [x0, x1, y0, y1] = scene.image.crop_pixels().map(i64::from);
    let (bw, bh, border) =
        (i64::from(frame.bucket_w), i64::from(frame.bucket_h), i64::from(frame.border));
    all.filter(|&b| {
        let (left, top) = frame.bucket_origin(b);
        let (l, t) = (i64::from(left) - border, i64::from(top) - border);
        let (r, d) = (l + bw + 2 * border, t + bh + 2 * border);
        l < x1 && r > x0 && t < y1 && d > y0
    })
    .collect()
}

/// Tile `i` of `n` (1-based) of `buckets`: the `i`-th of `n` runs of consecutive buckets in
/// raster order, their lengths differing by at most one (the first `len % n` runs are the
/// longer). None unless `1 <= i <= n <= buckets.len()`.
pub fn tile(buckets: &[usize], i: usize, n: usize) -> Option<&[usize]> {
    if i == 0 || i > n || n > buckets.len() {
        return None;
    }
    let (q, r) = (buckets.len() / n, buckets.len() % n);
    let start = (i - 1) * q + (i - 1).min(r);
    let len = q + usize::from(i - 1 < r);
    Some(&buckets[start..start + len])
}

/// The frame of `width x height` pixels (and `aov_channels` AOV channels, if any) that the
/// bucket `results` make, added in the order given, which must be bucket raster order for
/// the sums to be the single render's.
pub fn assemble<'a>(
    width: u32,
    height: u32,
    aov_channels: Option<usize>,
    results: impl IntoIterator<Item = &'a BucketResult>,
) -> (Film, Option<AovFilm>) {
    let mut film = Film::new(width, height);
    let mut aovs = aov_channels.map(|c| AovFilm::new(width, height, c));
    for r in results {
        add(&mut film, aovs.as_mut(), r);
    }
    (film, aovs)
}

/// Add one bucket's result to the frame.
pub(crate) fn add(film: &mut Film, aovs: Option<&mut AovFilm>, r: &BucketResult) {
    if let Some(w) = &r.window {
        film.add(w);
    }
    if let (Some(f), Some(w)) = (aovs, &r.aov) {
        f.add(w);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_partition_the_buckets_in_order() {
        let buckets: Vec<usize> = (10..33).collect();
        for n in 1..=buckets.len() {
            let mut joined = Vec::new();
            let mut lens = Vec::new();
            for i in 1..=n {
                let t = tile(&buckets, i, n).unwrap_or_else(|| panic!("{i}/{n}"));
                lens.push(t.len());
                joined.extend_from_slice(t);
            }
            assert_eq!(joined, buckets, "n = {n}");
            let (lo, hi) = (lens.iter().min().copied(), lens.iter().max().copied());
            assert!(hi.zip(lo).is_some_and(|(h, l)| h - l <= 1), "{lens:?}");
        }
        assert_eq!(tile(&buckets, 0, 3), None);
        assert_eq!(tile(&buckets, 4, 3), None);
        assert_eq!(tile(&buckets, 1, 24), None);
    }
}

//! Bucket files (stage: film, instead of the frame's output when a render is a piece of a
//! frame): a tile of a farm render, or one finished bucket of a checkpoint, as a multi-part
//! OpenEXR file from which the whole frame is reassembled exactly (docs/farm.md).
//!
//! Layout: part 0, named `tile`, is a picture of what the piece drew (the sum of its windows
//! over the pixels they cover, R, G, B, A and Z), for a person to look at, and carries the
//! caller's header text in the attribute `reyesTile`. Then one part per bucket that drew
//! anything, named `bucket.N` (N its raster index), whose data window is the bucket's whole
//! window (the bucket and the filter's border, which may reach off the image): channels R,
//! G, B, A, Z when the beauty drew, `aov.NNN` for each AOV channel when the frame has AOVs.
//! A bucket with no part drew nothing.
//!
//! Invariants: every value is stored as 32-bit float with lossless compression, so the
//! windows read back bit for bit; writes are atomic ([`crate::atomic`]), so a bucket file
//! either is complete or does not exist.

use std::io::{Seek, Write};
use std::path::Path;

use exr::prelude::*;

use crate::atomic::{WriteOptions, write_atomic};
use crate::output::{exr_error, io_error, read_all_parts};
use crate::{AovWindow, Film, FilmError, Window};

/// The attribute of part 0 that holds the header text.
const HEADER: &str = "reyesTile";

/// One bucket's windows, as stored.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StoredBucket {
    /// The bucket's raster index.
    pub bucket: usize,
    /// The beauty's window.
    pub window: Option<Window>,
    /// The AOVs' window.
    pub aov: Option<AovWindow>,
}

/// A bucket file read back: its header text and its buckets in the order stored.
#[derive(Debug, Clone, PartialEq)]
pub struct BucketFile {
    /// The caller's header (`reyesTile`).
    pub header: String,
    /// The buckets that drew anything.
    pub buckets: Vec<StoredBucket>,
}

/// Write `buckets` to `path` with the header text `header` (ASCII) and the picture
/// `preview`, whose top-left pixel is at raster `origin` of a frame of size `full`.
///
/// # Errors
///
/// [`FilmError::Io`] or [`FilmError::Exr`] as [`crate::write_with`]; [`FilmError::BadExr`]
/// if the header is not ASCII.
pub fn write_buckets(
    path: &Path,
    header: &str,
    (preview, origin, full): (&Film, (u32, u32), (u32, u32)),
    buckets: &[StoredBucket],
    opts: &WriteOptions,
) -> std::result::Result<(), FilmError> {
    let text = Text::new_or_none(header).filter(|_| header.is_ascii()).ok_or_else(|| {
        FilmError::BadExr {
            path: path.to_path_buf(),
            reason: "the tile header is not ASCII".into(),
        }
    })?;
    write_atomic(path, opts, &|w| encode(path, &text, (preview, origin, full), buckets, w))
}

fn f32s(values: impl Iterator<Item = f32>) -> FlatSamples {
    FlatSamples::F32(values.collect())
}

fn layer(
    name: &str,
    position: (i32, i32),
    size: (usize, usize),
    channels: Vec<AnyChannel<FlatSamples>>,
) -> Layer<AnyChannels<FlatSamples>> {
    let mut a = LayerAttributes::named(name);
    a.layer_position = Vec2(position.0, position.1);
    Layer::new(size, a, Encoding::SMALL_LOSSLESS, AnyChannels::sort(SmallVec::from_vec(channels)))
}

fn beauty(rgba: &[[f32; 4]], z: &[f32]) -> Vec<AnyChannel<FlatSamples>> {
    let plane = |k: usize| f32s(rgba.iter().map(move |p| p[k]));
    vec![
        AnyChannel::new("R", plane(0)),
        AnyChannel::new("G", plane(1)),
        AnyChannel::new("B", plane(2)),
        AnyChannel::new("A", plane(3)),
        AnyChannel::new("Z", f32s(z.iter().copied())),
    ]
}

fn encode(
    path: &Path,
    header: &Text,
    (preview, origin, full): (&Film, (u32, u32), (u32, u32)),
    buckets: &[StoredBucket],
    w: &mut (impl Write + Seek),
) -> std::result::Result<(), FilmError> {
    let size = (preview.width() as usize, preview.height() as usize);
    let mut first = layer(
        "tile",
        (origin.0 as i32, origin.1 as i32),
        size,
        beauty(preview.rgba(), preview.z()),
    );
    first.attributes.other.insert(Text::from(HEADER), AttributeValue::Text(header.clone()));
    let mut layers = vec![first];
    for b in buckets {
        let mut channels = Vec::new();
        let mut place = None;
        if let Some(win) = &b.window {
            channels.extend(beauty(&win.rgba, &win.z));
            place = Some((win.x0, win.y0, win.w, win.h));
        }
        if let Some(aov) = &b.aov {
            for c in 0..aov.channels {
                let values = aov.data.iter().skip(c).step_by(aov.channels.max(1)).copied();
                channels.push(AnyChannel::new(format!("aov.{c:03}").as_str(), f32s(values)));
            }
            let here = (aov.x0, aov.y0, aov.w, aov.h);
            if place.is_some_and(|p| p != here) {
                return Err(FilmError::BadExr {
                    path: path.to_path_buf(),
                    reason: format!("bucket {}: its beauty and AOV windows differ", b.bucket),
                });
            }
            place = Some(here);
        }
        let Some((x0, y0, ww, wh)) = place else { continue };
        let name = format!("bucket.{}", b.bucket);
        layers.push(layer(&name, (x0, y0), (ww as usize, wh as usize), channels));
    }
    let bounds = IntegerBounds::new((0, 0), (full.0 as usize, full.1 as usize));
    let image = Image::from_layers(ImageAttributes::new(bounds), layers);
    let mut bytes = std::io::Cursor::new(Vec::new());
    image.write().to_buffered(&mut bytes).map_err(|e| exr_error(path, e))?;
    w.write_all(&bytes.into_inner()).map_err(|e| io_error(path, e))
}

/// Read the bucket file `path` written by [`write_buckets`].
///
/// # Errors
///
/// [`FilmError::Io`] if it cannot be read, [`FilmError::Exr`] if it is not OpenEXR,
/// [`FilmError::BadExr`] if it is OpenEXR but not a bucket file (no `reyesTile` header, a
/// part that is not a bucket, channels missing).
pub fn read_buckets(path: &Path) -> std::result::Result<BucketFile, FilmError> {
    let image = read_all_parts(path)?;
    let bad = |reason: String| FilmError::BadExr { path: path.to_path_buf(), reason };
    let mut layers = image.layer_data.iter();
    let first = layers.next().ok_or_else(|| bad("no parts".into()))?;
    let header = match first.attributes.other.get(&Text::from(HEADER)) {
        Some(AttributeValue::Text(t))
            if first.attributes.layer_name == Some(Text::from("tile")) =>
        {
            String::from_utf8_lossy(t.bytes()).into_owned()
        }
        _ => return Err(bad("not a reyes-render tile (its first part has no reyesTile)".into())),
    };
    let mut buckets = Vec::new();
    for l in layers {
        let name = l.attributes.layer_name.as_ref().map(Text::to_string).unwrap_or_default();
        let bucket = name
            .strip_prefix("bucket.")
            .and_then(|n| n.parse().ok())
            .ok_or_else(|| bad(format!("part '{name}' is not a bucket")))?;
        let (x0, y0) = (l.attributes.layer_position.0, l.attributes.layer_position.1);
        let (w, h) = (l.size.0 as u32, l.size.1 as u32);
        let channel = |n: &str| -> Option<Vec<f32>> {
            let c = l.channel_data.list.iter().find(|c| c.name.eq(n))?;
            match &c.sample_data {
                FlatSamples::F32(v) => Some(v.clone()),
                _ => None,
            }
        };
        let window = match (channel("R"), channel("G"), channel("B"), channel("A"), channel("Z")) {
            (Some(r), Some(g), Some(b), Some(a), Some(z)) => Some(Window {
                x0,
                y0,
                w,
                h,
                rgba: (0..z.len()).map(|k| [r[k], g[k], b[k], a[k]]).collect(),
                z,
            }),
            (None, None, None, None, None) => None,
            _ => return Err(bad(format!("part '{name}': R, G, B, A or Z missing"))),
        };
        let mut planes = Vec::new();
        while let Some(v) = channel(&format!("aov.{:03}", planes.len())) {
            planes.push(v);
        }
        let aov = (!planes.is_empty()).then(|| {
            let n = planes[0].len();
            let data = (0..n).flat_map(|k| planes.iter().map(move |p| p[k])).collect();
            AovWindow { x0, y0, w, h, channels: planes.len(), data }
        });
        buckets.push(StoredBucket { bucket, window, aov });
    }
    Ok(BucketFile { header, buckets })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_round_trip_bit_for_bit() {
        let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
        let path = dir.path().join("t.exr");
        let n = 4 * 3;
        let odd = |k: usize| f32::from_bits(0x3f80_0001 + k as u32 * 977) * (-1f32).powi(k as i32);
        let window = Window {
            x0: -1,
            y0: 5,
            w: 4,
            h: 3,
            rgba: (0..n).map(|k| [odd(k), -0.0, odd(k + 1), 1.0]).collect(),
            z: (0..n).map(|k| if k % 2 == 0 { f32::INFINITY } else { odd(k) }).collect(),
        };
        let aov = AovWindow {
            x0: -1,
            y0: 5,
            w: 4,
            h: 3,
            channels: 2,
            data: (0..2 * n).map(odd).collect(),
        };
        let buckets = vec![
            StoredBucket { bucket: 3, window: Some(window.clone()), aov: Some(aov.clone()) },
            StoredBucket { bucket: 7, window: None, aov: Some(aov) },
            StoredBucket { bucket: 9, window: Some(window), aov: None },
        ];
        let preview = Film::new(2, 2);
        let header = "(tile: (1, 2))";
        write_buckets(&path, header, (&preview, (3, 4), (10, 10)), &buckets, &Default::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let back = read_buckets(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back.header, header);
        let bits = |b: &[StoredBucket]| format!("{b:?}");
        assert_eq!(back.buckets.len(), 3);
        for (a, b) in back.buckets.iter().zip(&buckets) {
            assert_eq!(a.bucket, b.bucket);
            let wa = a.window.as_ref().map(|w| {
                (
                    w.rgba.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    w.z.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    (w.x0, w.y0, w.w, w.h),
                )
            });
            let wb = b.window.as_ref().map(|w| {
                (
                    w.rgba.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    w.z.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    (w.x0, w.y0, w.w, w.h),
                )
            });
            assert_eq!(wa, wb, "{}", bits(&back.buckets));
            assert_eq!(
                a.aov.as_ref().map(|w| w.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>()),
                b.aov.as_ref().map(|w| w.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
            );
        }
        // An ordinary image is not a bucket file.
        let plain = dir.path().join("plain.exr");
        crate::write(&plain, &preview).unwrap_or_else(|e| panic!("{e}"));
        let e = read_buckets(&plain).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(e.contains("not a reyes-render tile"), "{e}");
    }
}

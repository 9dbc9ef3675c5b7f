//! Image file output (stage: film, the very last step of a frame) and EXR read-back.
//!
//! Invariants: writes are atomic ([`crate::atomic`]). The image is encoded into a temporary
//! file in the target's own directory (unnamed where the system allows), flushed and synced,
//! then given the target's name; on any error or cancellation the target is untouched (absent
//! if it did not exist) and the temporary file is removed. The format is
//! chosen by the extension alone: `.exr` (float R, G, B, A premultiplied linear, plus Z) or
//! `.png` (8-bit straight sRGB colour, linear alpha).

use std::ffi::OsStr;
use std::io::{Seek, Write};
use std::path::{Path, PathBuf};

use crate::atomic::{WriteOptions, write_atomic};
use crate::{Film, FilmError};

/// Output formats, chosen by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Format {
    Exr,
    Png,
}

pub(crate) fn format_of(path: &Path) -> Result<Format, FilmError> {
    let ext = path.extension().and_then(OsStr::to_str).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("exr") => Ok(Format::Exr),
        Some("png") => Ok(Format::Png),
        _ => Err(FilmError::UnknownFormat { path: path.to_path_buf() }),
    }
}

/// Write `film` to `path`, atomically, as OpenEXR or PNG according to the extension
/// (case-insensitive).
///
/// The output step after Appendix A's `DisplayWindow` (3.17), which the listing leaves to the
/// display module. `.exr`: 32-bit float channels R, G, B, A (premultiplied, linear) and Z
/// (`+inf` where no opaque surface), lossless ZIP compression. `.png`: 8-bit RGBA, colour
/// un-premultiplied and encoded with the sRGB curve, alpha linear; values are clamped to
/// `[0, 1]` and colour is 0 where alpha is not positive.
///
/// # Errors
///
/// [`FilmError::UnknownFormat`] for any other extension (nothing is created);
/// [`FilmError::Io`] if the directory is missing or unwritable or the write/rename fails;
/// [`FilmError::Exr`] / [`FilmError::Png`] if the encoder rejects the image (e.g. 0 pixels).
pub fn write(path: &Path, film: &Film) -> Result<(), FilmError> {
    write_with(path, film, &WriteOptions::default())
}

/// [`write()`] with options: a cancel flag polled between chunks, a test hook, the named
/// temporary file forced (see [`WriteOptions`] and [`crate::atomic`]).
///
/// # Errors
///
/// Those of [`write()`], and [`FilmError::Interrupted`] when `opts.cancel` was set before the
/// file was complete (the target is then untouched and no temporary file remains).
pub fn write_with(path: &Path, film: &Film, opts: &WriteOptions) -> Result<(), FilmError> {
    match format_of(path)? {
        Format::Exr => write_atomic(path, opts, &|w| encode_exr(path, film, w)),
        Format::Png => write_atomic(path, opts, &|w| encode_png(path, film, w)),
    }
}

/// Every channel of every part of the OpenEXR file `path`, at full resolution.
pub(crate) fn read_all_parts(path: &Path) -> Result<exr::image::FlatImage, FilmError> {
    use exr::prelude::*;
    read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_file(path)
        .map_err(|e| exr_error(path, e))
}

pub(crate) fn io_error(path: &Path, source: std::io::Error) -> FilmError {
    FilmError::Io { path: path.to_path_buf(), source }
}

pub(crate) fn exr_error(path: &Path, source: exr::error::Error) -> FilmError {
    match source {
        exr::error::Error::Io(source) => io_error(path, source),
        source => FilmError::Exr { path: path.to_path_buf(), source },
    }
}

fn encode_exr(path: &Path, film: &Film, w: &mut (impl Write + Seek)) -> Result<(), FilmError> {
    use exr::prelude::*;
    let size = (film.width() as usize, film.height() as usize);
    let (rgba, z) = (film.rgba(), film.z());
    // Pixels are read from the film as the encoder asks for them, block by block, instead
    // of copying the image into five planes first (6 MB at 640x480).
    let channels = SpecificChannels::build()
        .with_channel("R")
        .with_channel("G")
        .with_channel("B")
        .with_channel("A")
        .with_channel("Z")
        .with_pixel_fn(|pos: Vec2<usize>| {
            let i = pos.y() * size.0 + pos.x();
            let p = rgba[i];
            (p[0], p[1], p[2], p[3], z[i])
        });
    // ZIP is lossless for f32, so the file round-trips bit-exactly.
    let layer = Layer::new(size, LayerAttributes::default(), Encoding::SMALL_LOSSLESS, channels);
    Image::from_layer(layer).write().to_buffered(w).map_err(|e| exr_error(path, e))
}

fn encode_png(path: &Path, film: &Film, w: &mut impl Write) -> Result<(), FilmError> {
    let mut bytes = Vec::with_capacity(film.rgba().len() * 4);
    for p in film.rgba() {
        bytes.extend_from_slice(&png_pixel(*p));
    }
    encode_png_bytes(path, film, &bytes, w)
}

/// The 8-bit RGBA of `film` through the view transform `view` ([`crate::view_pixel`]).
pub(crate) fn png_bytes(film: &Film, view: &reyes_scene::PngView) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(film.rgba().len() * 4);
    let w = film.width().max(1) as usize;
    for (i, p) in film.rgba().iter().enumerate() {
        let (x, y) = ((i % w) as u32, (i / w) as u32);
        bytes.extend_from_slice(&crate::view_pixel(*p, (x, y), view));
    }
    bytes
}

/// Encode 8-bit RGBA `bytes` of `film`'s size as PNG.
pub(crate) fn encode_png_bytes(
    path: &Path,
    film: &Film,
    bytes: &[u8],
    w: &mut impl Write,
) -> Result<(), FilmError> {
    use image::ImageEncoder;
    image::codecs::png::PngEncoder::new(w)
        .write_image(bytes, film.width(), film.height(), image::ExtendedColorType::Rgba8)
        .map_err(|e| match e {
            image::ImageError::IoError(source) => io_error(path, source),
            source => FilmError::Png { path: path.to_path_buf(), source },
        })
}

/// One premultiplied linear pixel to 8-bit straight sRGB colour and linear alpha.
pub(crate) fn png_pixel(p: [f32; 4]) -> [u8; 4] {
    let a = p[3];
    let straight = |c: f32| if a > 0.0 { c / a } else { 0.0 };
    [
        quantise(srgb_encode(straight(p[0]))),
        quantise(srgb_encode(straight(p[1]))),
        quantise(srgb_encode(straight(p[2]))),
        quantise(a),
    ]
}

/// `[0, 1]` (clamped; NaN as 0) to the nearest of 0..=255.
fn quantise(v: f32) -> u8 {
    if v.is_nan() { 0 } else { (v.clamp(0.0, 1.0) * 255.0).round() as u8 }
}

/// The sRGB transfer function (IEC 61966-2-1): linear light to encoded value. Values outside
/// `[0, 1]` are clamped first.
pub fn srgb_encode(linear: f32) -> f32 {
    let v = f64::from(linear.clamp(0.0, 1.0));
    let e = if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
    e as f32
}

/// The inverse sRGB transfer function: encoded value to linear light. Values outside `[0, 1]`
/// are clamped first.
pub fn srgb_decode(encoded: f32) -> f32 {
    let e = f64::from(encoded.clamp(0.0, 1.0));
    let v = if e <= 0.040_45 { e / 12.92 } else { ((e + 0.055) / 1.055).powf(2.4) };
    v as f32
}

/// Read back an OpenEXR file written by [`write()`]: channels R, G, B, A (required) and Z
/// (optional; `+inf` where absent), of the first valid layer.
///
/// Used by golden-image tests; not a general EXR importer.
///
/// # Errors
///
/// [`FilmError::Io`] if the file cannot be read, [`FilmError::Exr`] if it is not valid
/// OpenEXR, [`FilmError::BadExr`] if a required channel is missing or too large.
pub fn read_exr(path: &Path) -> Result<Film, FilmError> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| exr_error(path, e))?;
    let layer = &image.layer_data;
    let bad = |reason: String| FilmError::BadExr { path: PathBuf::from(path), reason };
    let (w, h) = (layer.size.width(), layer.size.height());
    let width = u32::try_from(w).map_err(|_| bad(format!("width {w} is too large")))?;
    let height = u32::try_from(h).map_err(|_| bad(format!("height {h} is too large")))?;
    let n = w * h;
    // `R`, or a layer's `NAME.R` when the file has no top-level R (Aqsis writes `layer_0.R`).
    let channel = |name: &str| -> Option<Vec<f32>> {
        let list = &layer.channel_data.list;
        let suffix = format!(".{name}");
        list.iter()
            .find(|c| c.name.eq(name))
            .or_else(|| list.iter().find(|c| c.name.to_string().ends_with(&suffix)))
            .map(|c| c.sample_data.values_as_f32().collect())
    };
    let mut rgba = vec![[0.0_f32; 4]; n];
    for (k, name) in ["R", "G", "B", "A"].into_iter().enumerate() {
        let values = channel(name).ok_or_else(|| bad(format!("no {name} channel")))?;
        if values.len() != n {
            return Err(bad(format!("channel {name} has {} samples, expected {n}", values.len())));
        }
        for (p, v) in rgba.iter_mut().zip(values) {
            p[k] = v;
        }
    }
    let z = match channel("Z") {
        Some(z) if z.len() == n => z,
        Some(z) => return Err(bad(format!("channel Z has {} samples, expected {n}", z.len()))),
        None => vec![f32::INFINITY; n],
    };
    Film::from_pixels(width, height, rgba, z)
        .ok_or_else(|| bad(format!("{w}x{h} pixels do not fit in memory")))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small film with varied values, including `+inf` depth, zeros, and a zero-alpha pixel.
    fn sample_film(width: u32, height: u32) -> Film {
        let n = (width * height) as usize;
        let rgba = (0..n)
            .map(|k| {
                let t = k as f32 / n as f32;
                let a = if k % 7 == 3 { 0.0 } else { 0.1 + 0.9 * ((k * 37 % 11) as f32 / 10.0) };
                [a * t, a * (1.0 - t), a * (0.3 + 0.7 * t * t), a]
            })
            .collect();
        let z =
            (0..n).map(|k| if k % 5 == 0 { f32::INFINITY } else { 1.0 + k as f32 / 3.0 }).collect();
        Film::from_pixels(width, height, rgba, z).unwrap_or_else(|| Film::new(width, height))
    }

    fn tmp_dir() -> tempfile::TempDir {
        tempfile::tempdir().unwrap_or_else(|e| panic!("cannot create a temporary directory: {e}"))
    }

    fn dir_entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .map(|rd| {
                rd.filter_map(|e| e.ok())
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .collect()
            })
            .unwrap_or_default();
        names.sort();
        names
    }

    #[test]
    fn exr_round_trips_bit_exactly() {
        let dir = tmp_dir();
        let film = sample_film(37, 23);
        for name in ["out.exr", "OUT.EXR", "mixed.Exr"] {
            let path = dir.path().join(name);
            write(&path, &film).unwrap_or_else(|e| panic!("{e}"));
            let back = read_exr(&path).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!((back.width(), back.height()), (film.width(), film.height()));
            let bits = |f: &Film| -> Vec<u32> {
                f.rgba().iter().flatten().chain(f.z()).map(|v| v.to_bits()).collect()
            };
            assert_eq!(bits(&back), bits(&film), "{name}");
        }
    }

    #[test]
    fn exr_without_z_reads_as_infinite_depth() {
        use exr::prelude::*;
        let dir = tmp_dir();
        let path = dir.path().join("noz.exr");
        let (w, h) = (3_usize, 2_usize);
        let plane = |v: f32| FlatSamples::F32(vec![v; w * h]);
        let channels = AnyChannels::sort(SmallVec::from_vec(vec![
            AnyChannel::new("R", plane(0.25)),
            AnyChannel::new("G", plane(0.5)),
            AnyChannel::new("B", plane(0.75)),
            AnyChannel::new("A", plane(1.0)),
        ]));
        let layer =
            Layer::new((w, h), LayerAttributes::default(), Encoding::UNCOMPRESSED, channels);
        Image::from_layer(layer).write().to_file(&path).unwrap_or_else(|e| panic!("{e}"));
        let film = read_exr(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(film.rgba().iter().all(|p| *p == [0.25, 0.5, 0.75, 1.0]));
        assert!(film.z().iter().all(|z| *z == f32::INFINITY));
    }

    #[test]
    fn png_round_trips_within_one_code() {
        let dir = tmp_dir();
        let film = sample_film(29, 17);
        let path = dir.path().join("out.PNG");
        write(&path, &film).unwrap_or_else(|e| panic!("{e}"));
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
        let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
            .unwrap_or_else(|e| panic!("{e}"))
            .to_rgba8();
        assert_eq!(img.dimensions(), (film.width(), film.height()));
        for (p, q) in film.rgba().iter().zip(img.pixels()) {
            let a = p[3];
            // Alpha is linear: within half a code.
            assert!((f32::from(q[3]) / 255.0 - a).abs() <= 0.5 / 255.0 + 1e-6, "{p:?} {q:?}");
            for k in 0..3 {
                let straight = if a > 0.0 { p[k] / a } else { 0.0 };
                let code = f32::from(q[k]);
                // Encoded value within half a code of the exact sRGB encoding ...
                assert!(
                    (code / 255.0 - srgb_encode(straight)).abs() <= 0.5 / 255.0 + 1e-6,
                    "{p:?} {q:?}"
                );
                // ... so after sRGB decode the colour lies between the decodes of the
                // neighbouring half codes, i.e. within one code of where it started.
                let lo = srgb_decode((code - 0.5) / 255.0);
                let hi = srgb_decode((code + 0.5) / 255.0);
                assert!(lo - 1e-6 <= straight && straight <= hi + 1e-6, "{p:?} {q:?} k={k}");
                assert!((srgb_decode(code / 255.0) - straight).abs() <= hi - lo + 1e-6);
            }
        }
    }

    #[test]
    fn png_values_are_straight_and_srgb() {
        // Premultiplied half-grey at 50% alpha is straight 1.0 -> 255; 0.5 alpha -> 128.
        assert_eq!(png_pixel([0.5, 0.25, 0.0, 0.5]), [255, quantise(srgb_encode(0.5)), 0, 128]);
        assert_eq!(quantise(srgb_encode(0.5)), 188);
        assert_eq!(png_pixel([0.3, 0.3, 0.3, 0.0]), [0, 0, 0, 0]);
        assert_eq!(png_pixel([2.0, -1.0, f32::NAN, 1.5]), [255, 0, 0, 255]);
        for k in 0..=255_u8 {
            let e = f32::from(k) / 255.0;
            assert_eq!(quantise(srgb_encode(srgb_decode(e))), k, "sRGB curve round trip at {k}");
        }
    }

    #[test]
    fn unknown_extension_is_rejected_and_creates_nothing() {
        let dir = tmp_dir();
        for name in ["out.tif", "out", "out.exr.bak"] {
            let path = dir.path().join(name);
            let r = write(&path, &sample_film(2, 2));
            assert!(matches!(r, Err(FilmError::UnknownFormat { .. })), "{name}: {r:?}");
        }
        assert!(dir_entries(dir.path()).is_empty());
    }

    #[test]
    fn unwritable_path_is_io_error_and_leaves_nothing() {
        let path = Path::new("/nonexistent-dir/x.exr");
        let r = write(path, &sample_film(2, 2));
        match r {
            Err(FilmError::Io { path: p, .. }) => assert_eq!(p, path),
            other => panic!("expected Io, got {other:?}"),
        }
        assert!(!path.exists());
        // The message is one line and names the path.
        let msg = write(path, &sample_film(2, 2)).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(msg.contains("/nonexistent-dir/x.exr") && !msg.contains('\n'), "{msg}");

        // A missing subdirectory of a real directory, and a PNG.
        let dir = tmp_dir();
        let path = dir.path().join("missing").join("x.png");
        assert!(matches!(write(&path, &sample_film(2, 2)), Err(FilmError::Io { .. })));
        assert!(dir_entries(dir.path()).is_empty());
    }

    #[test]
    fn failed_rename_leaves_no_temporary() {
        // The target is an existing non-empty directory: the rename fails after encoding.
        let dir = tmp_dir();
        let target = dir.path().join("taken.exr");
        std::fs::create_dir(&target).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(target.join("keep"), b"x").unwrap_or_else(|e| panic!("{e}"));
        let r = write(&target, &sample_film(3, 3));
        assert!(matches!(r, Err(FilmError::Io { .. })), "{r:?}");
        assert_eq!(dir_entries(dir.path()), vec!["taken.exr".to_string()]);
        assert!(target.is_dir());
    }

    #[test]
    fn encoder_error_leaves_nothing() {
        // A 0x0 image is rejected by the encoders after the temporary file exists.
        let dir = tmp_dir();
        for name in ["empty.exr", "empty.png"] {
            let path = dir.path().join(name);
            let r = write(&path, &Film::new(0, 0));
            assert!(r.is_err(), "{name}: {r:?}");
            assert!(!matches!(r, Err(FilmError::UnknownFormat { .. })));
        }
        assert!(dir_entries(dir.path()).is_empty());
    }

    #[test]
    fn overwrite_replaces_atomically() {
        let dir = tmp_dir();
        let path = dir.path().join("frame.exr");
        std::fs::write(&path, b"not an image").unwrap_or_else(|e| panic!("{e}"));
        let first = sample_film(8, 4);
        write(&path, &first).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(read_exr(&path).ok(), Some(first));
        let second = Film::new(5, 6);
        write(&path, &second).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(read_exr(&path).ok(), Some(second));
        assert_eq!(dir_entries(dir.path()), vec!["frame.exr".to_string()]);

        // Same for PNG.
        let png = dir.path().join("frame.png");
        std::fs::write(&png, b"old").unwrap_or_else(|e| panic!("{e}"));
        write(&png, &sample_film(4, 4)).unwrap_or_else(|e| panic!("{e}"));
        let bytes = std::fs::read(&png).unwrap_or_default();
        assert!(bytes.starts_with(b"\x89PNG"));
        assert_eq!(dir_entries(dir.path()), vec!["frame.exr".to_string(), "frame.png".to_string()]);
    }

    #[test]
    fn format_follows_extension_case_insensitively() {
        assert_eq!(format_of(Path::new("a.ExR")).ok(), Some(Format::Exr));
        assert_eq!(format_of(Path::new("dir/a.png")).ok(), Some(Format::Png));
    }
}

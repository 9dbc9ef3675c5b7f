//! Decoding a texture file into linear RGBA `f32`: OpenEXR through the `exr` crate (its
//! first RGBA layer), PNG, JPEG and TIFF through the `image` crate (8- and 16-bit, grey or
//! colour, with or without alpha; 8-bit values are `v / 255`, 16-bit `v / 65535`), then the
//! declared colour space's transfer function on the colour channels.
//!
//! Invariants: a missing or unreadable file is [`TextureError::Io`]; anything else wrong
//! (an unknown format, a truncated or corrupt image, an empty image, one over
//! [`MAX_SIDE`] texels a side) is [`TextureError::Decode`]; non-finite values become 0. No
//! decoder allocates for a picture larger than that: the `image` crate's default limits
//! (512 MiB) hold for PNG, JPEG and TIFF, and an OpenEXR header is checked before its pixels
//! are read.

use std::io::Read;
use std::path::Path;

use crate::{ColorSpace, TextureError};

/// The largest side accepted, in texels (a pyramid's tile indices and sizes stay in range).
pub const MAX_SIDE: u32 = 1 << 16;

/// An image in linear RGBA `f32`, row by row from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Texels across.
    pub width: u32,
    /// Texels down.
    pub height: u32,
    /// `4 * width * height` floats.
    pub texels: Vec<f32>,
}

impl Image {
    /// Smallest and largest value of each channel.
    pub fn range(&self) -> ([f32; 4], [f32; 4]) {
        let (mut lo, mut hi) = ([f32::INFINITY; 4], [f32::NEG_INFINITY; 4]);
        for px in self.texels.chunks_exact(4) {
            for c in 0..4 {
                lo[c] = lo[c].min(px[c]);
                hi[c] = hi[c].max(px[c]);
            }
        }
        (lo, hi)
    }
}

/// The sRGB transfer function, encoded value to linear light (IEC 61966-2-1).
pub fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 { v / 12.92 } else { ((v + 0.055) / 1.055).powf(2.4) }
}

/// Decode `file`, declared to be in `space`.
pub fn decode(file: &Path, space: ColorSpace) -> Result<Image, TextureError> {
    let bad = |message: String| TextureError::Decode { file: file.to_path_buf(), message };
    let io = |source| TextureError::Io { file: file.to_path_buf(), source };
    let mut head = [0u8; 4];
    let n = std::fs::File::open(file).and_then(|mut f| f.read(&mut head)).map_err(io)?;
    let is_exr = n == 4 && head == [0x76, 0x2f, 0x31, 0x01];
    let mut image = if is_exr { decode_exr(file).map_err(bad)? } else { decode_image(file)? };
    if image.width == 0 || image.height == 0 {
        return Err(bad("the image is empty".into()));
    }
    if image.width > MAX_SIDE || image.height > MAX_SIDE {
        return Err(bad(format!(
            "{} x {} texels is over the limit of {MAX_SIDE} a side",
            image.width, image.height
        )));
    }
    for px in image.texels.chunks_exact_mut(4) {
        for (c, v) in px.iter_mut().enumerate() {
            if !v.is_finite() {
                *v = 0.0;
            } else if c < 3 && space == ColorSpace::Srgb {
                *v = srgb_to_linear(*v);
            }
        }
    }
    Ok(image)
}

fn decode_image(file: &Path) -> Result<Image, TextureError> {
    let bad = |message: String| TextureError::Decode { file: file.to_path_buf(), message };
    let reader = image::ImageReader::open(file)
        .map_err(|source| TextureError::Io { file: file.to_path_buf(), source })?
        .with_guessed_format()
        .map_err(|source| TextureError::Io { file: file.to_path_buf(), source })?;
    if reader.format().is_none() {
        return Err(bad("not a PNG, JPEG, TIFF or OpenEXR file".into()));
    }
    let decoded = reader.decode().map_err(|e| match e {
        image::ImageError::IoError(source)
            if source.kind() != std::io::ErrorKind::UnexpectedEof =>
        {
            TextureError::Io { file: file.to_path_buf(), source }
        }
        other => bad(format!("cannot decode: {other}")),
    })?;
    let rgba = decoded.to_rgba32f();
    Ok(Image { width: rgba.width(), height: rgba.height(), texels: rgba.into_raw() })
}

fn decode_exr(file: &Path) -> Result<Image, String> {
    // The header first: refuse an over-size image before allocating its pixels.
    let meta = exr::meta::MetaData::read_from_file(file, false)
        .map_err(|e| format!("cannot decode OpenEXR: {e}"))?;
    for header in &meta.headers {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        if w > MAX_SIDE as usize || h > MAX_SIDE as usize {
            return Err(format!("{w} x {h} texels is over the limit of {MAX_SIDE} a side"));
        }
    }
    let image = exr::prelude::read_first_rgba_layer_from_file(
        file,
        |resolution, _| Image {
            width: resolution.width() as u32,
            height: resolution.height() as u32,
            texels: vec![0.0; resolution.width() * resolution.height() * 4],
        },
        |image: &mut Image, pos: exr::prelude::Vec2<usize>, (r, g, b, a): (f32, f32, f32, f32)| {
            let k = 4 * (pos.y() * image.width as usize + pos.x());
            image.texels[k..k + 4].copy_from_slice(&[r, g, b, a]);
        },
    )
    .map_err(|e| format!("cannot decode OpenEXR: {e}"))?;
    Ok(image.layer_data.channel_data.pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_curve_ends_and_middle() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        // 188/255 is the sRGB code of linear 0.5 (to within its step).
        assert!((srgb_to_linear(188.0 / 255.0) - 0.5).abs() < 0.003);
    }

    #[test]
    fn errors_name_the_file_and_tell_io_from_bad_data() {
        let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
        let missing = dir.path().join("missing.png");
        let e = decode(&missing, ColorSpace::Srgb).err().unwrap_or_else(|| panic!("decoded"));
        assert_eq!(e.exit_code(), 1);
        assert!(e.to_string().starts_with(&format!("{}: texture: cannot read", missing.display())));
        let junk = dir.path().join("junk.png");
        std::fs::write(&junk, b"\x89PNG\r\n\x1a\nnot really").unwrap_or_else(|e| panic!("{e}"));
        let e = decode(&junk, ColorSpace::Srgb).err().unwrap_or_else(|| panic!("decoded"));
        assert_eq!(e.exit_code(), 2, "{e}");
        assert!(e.to_string().starts_with(&format!("{}: texture: ", junk.display())), "{e}");
        let text = dir.path().join("notes.txt");
        std::fs::write(&text, b"hello").unwrap_or_else(|e| panic!("{e}"));
        let e = decode(&text, ColorSpace::Linear).err().unwrap_or_else(|| panic!("decoded"));
        assert_eq!(e.exit_code(), 2, "{e}");
    }
}

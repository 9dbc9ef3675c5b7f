//! Writing prepared textures: a tiled TIFF with one directory per MIP level, finest first,
//! 32 x 32 tiles, uncompressed, with Pixar's tags (texture format, wrap modes, the shadow
//! matrices, the cube faces' field of view), the layout `txmake` and the peers write, so that
//! other RenderMan tools read our files and [`crate::prepared`] reads theirs.
//!
//! Invariants: the file appears complete or not at all (written to a temporary file beside it,
//! then renamed); a float file holds the levels' values exactly; an 8-bit file holds
//! `round(255 clamp(v, 0, 1))`, a 16-bit one `round(65535 clamp(v, 0, 1))`, a half file the
//! nearest half float.

use std::io::{BufWriter, Seek, Write};
use std::path::Path;

use tiff::encoder::TiffEncoder;
use tiff::tags::{CompressionMethod, ExtraSamples, PhotometricInterpretation, SampleFormat, Tag};

use crate::Wrap;
use crate::mip::MipLevel;
use crate::prepared::{
    MapKind, TAG_FOVCOT, TAG_TEXTUREFORMAT, TAG_WORLDTOCAMERA, TAG_WORLDTOSCREEN, TAG_WRAPMODES,
};

/// Tile side of the files we write (TIFF wants a multiple of 16; the peers write 32).
pub const FILE_TILE: u32 = 32;

/// How samples are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Depth {
    /// 8-bit unsigned, `v / 255` (`--byte`).
    Byte,
    /// 16-bit unsigned, `v / 65535` (`--short`).
    Short,
    /// 16-bit float (`--half`).
    Half,
    /// 32-bit float (`--float`).
    Float,
}

/// What a prepared file says about itself.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// What the map is for.
    pub kind: MapKind,
    /// Wrap modes in s and t.
    pub wrap: [Wrap; 2],
    /// Sample storage.
    pub depth: Depth,
    /// Channels to write (1 to 4) of the levels' RGBA.
    pub channels: u32,
    /// Shadow maps: world to the light's screen space, and to its camera space (row vectors).
    pub matrices: Option<([f32; 16], [f32; 16])>,
    /// Cube-face maps: the cotangent of half the faces' field of view.
    pub fov_cot: Option<f32>,
}

/// The word RenderMan writes for a wrap mode.
pub fn wrap_word(w: Wrap) -> &'static str {
    match w {
        Wrap::Periodic => "periodic",
        Wrap::Clamp => "clamp",
        Wrap::Black => "black",
    }
}

/// Samples of tile `(tx, ty)` of `level` in `spec`'s depth, as bytes in the file's (native)
/// byte order; texels past the edge are 0.
fn tile_bytes(level: &MipLevel, tx: u32, ty: u32, spec: &Spec) -> Vec<u8> {
    let c = spec.channels as usize;
    let n = (FILE_TILE * FILE_TILE) as usize * c;
    let mut values = vec![0.0f32; n];
    for row in 0..FILE_TILE {
        let y = ty * FILE_TILE + row;
        if y >= level.height {
            break;
        }
        for col in 0..FILE_TILE {
            let x = tx * FILE_TILE + col;
            if x >= level.width {
                break;
            }
            let k = 4 * (y as usize * level.width as usize + x as usize);
            let o = c * (row * FILE_TILE + col) as usize;
            values[o..o + c].copy_from_slice(&level.texels[k..k + c]);
        }
    }
    let unit = |v: f32, max: f32| (v.clamp(0.0, 1.0) * max).round();
    match spec.depth {
        Depth::Byte => values.iter().map(|&v| unit(v, 255.0) as u8).collect(),
        Depth::Short => {
            values.iter().flat_map(|&v| (unit(v, 65535.0) as u16).to_ne_bytes()).collect()
        }
        Depth::Half => values.iter().flat_map(|&v| half::f16::from_f32(v).to_ne_bytes()).collect(),
        Depth::Float => values.iter().flat_map(|&v| v.to_ne_bytes()).collect(),
    }
}

/// Writes `levels` (finest first, RGBA) to `path` as a prepared texture.
///
/// # Errors
///
/// The file cannot be written (an I/O error), or `levels` is empty.
pub fn write(path: &Path, levels: &[MipLevel], spec: &Spec) -> std::io::Result<()> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut temp = tempfile::NamedTempFile::new_in(dir)?;
    write_to(temp.as_file_mut(), levels, spec)?;
    temp.as_file_mut().flush()?;
    // A temporary file is private (0600); a texture is for others to read too.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        temp.as_file().set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    temp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// [`write`] to an open stream.
///
/// # Errors
///
/// As [`write`].
pub fn write_to<W: Write + Seek>(out: W, levels: &[MipLevel], spec: &Spec) -> std::io::Result<()> {
    let err = |e: tiff::TiffError| std::io::Error::other(e.to_string());
    if levels.is_empty() || !(1..=4).contains(&spec.channels) {
        return Err(std::io::Error::other("nothing to write"));
    }
    let mut enc = TiffEncoder::new(BufWriter::new(out)).map_err(err)?;
    let c = spec.channels as usize;
    let (bits, format): (u16, SampleFormat) = match spec.depth {
        Depth::Byte => (8, SampleFormat::Uint),
        Depth::Short => (16, SampleFormat::Uint),
        Depth::Half => (16, SampleFormat::IEEEFP),
        Depth::Float => (32, SampleFormat::IEEEFP),
    };
    let wraps = format!("{},{}", wrap_word(spec.wrap[0]), wrap_word(spec.wrap[1]));
    for (k, level) in levels.iter().enumerate() {
        let mut d = enc.image_directory().map_err(err)?;
        let (tiles_x, tiles_y) =
            (level.width.div_ceil(FILE_TILE), level.height.div_ceil(FILE_TILE));
        let mut offsets = Vec::new();
        let mut counts = Vec::new();
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                let bytes = tile_bytes(level, tx, ty, spec);
                let at = d.write_data(&bytes[..]).map_err(err)?;
                offsets.push(u32::try_from(at).map_err(|_| std::io::Error::other("over 4 GB"))?);
                counts.push(bytes.len() as u32);
            }
        }
        d.write_tag(Tag::NewSubfileType, if k == 0 { 0u32 } else { 1u32 }).map_err(err)?;
        d.write_tag(Tag::ImageWidth, level.width).map_err(err)?;
        d.write_tag(Tag::ImageLength, level.height).map_err(err)?;
        d.write_tag(Tag::BitsPerSample, &vec![bits; c][..]).map_err(err)?;
        d.write_tag(Tag::Compression, CompressionMethod::None).map_err(err)?;
        let photometric = if c >= 3 {
            PhotometricInterpretation::RGB
        } else {
            PhotometricInterpretation::BlackIsZero
        };
        d.write_tag(Tag::PhotometricInterpretation, photometric).map_err(err)?;
        d.write_tag(Tag::SamplesPerPixel, spec.channels as u16).map_err(err)?;
        d.write_tag(Tag::PlanarConfiguration, 1u16).map_err(err)?;
        d.write_tag(Tag::SampleFormat, &vec![format; c][..]).map_err(err)?;
        if c == 2 || c == 4 {
            d.write_tag(Tag::ExtraSamples, &[ExtraSamples::AssociatedAlpha][..]).map_err(err)?;
        }
        d.write_tag(Tag::TileWidth, FILE_TILE).map_err(err)?;
        d.write_tag(Tag::TileLength, FILE_TILE).map_err(err)?;
        d.write_tag(Tag::TileOffsets, &offsets[..]).map_err(err)?;
        d.write_tag(Tag::TileByteCounts, &counts[..]).map_err(err)?;
        d.write_tag(Tag::Software, "reyes-render").map_err(err)?;
        d.write_tag(Tag::Unknown(TAG_TEXTUREFORMAT), spec.kind.format()).map_err(err)?;
        d.write_tag(Tag::Unknown(TAG_WRAPMODES), wraps.as_str()).map_err(err)?;
        if let Some(f) = spec.fov_cot {
            d.write_tag(Tag::Unknown(TAG_FOVCOT), f).map_err(err)?;
        }
        if let Some((screen, camera)) = &spec.matrices {
            d.write_tag(Tag::Unknown(TAG_WORLDTOSCREEN), &screen[..]).map_err(err)?;
            d.write_tag(Tag::Unknown(TAG_WORLDTOCAMERA), &camera[..]).map_err(err)?;
        }
        d.finish().map_err(err)?;
    }
    Ok(())
}

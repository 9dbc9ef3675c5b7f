//! Making prepared textures from pictures: RenderMan's `MakeTexture`,
//! `MakeLatLongEnvironment`, `MakeCubeFaceEnvironment` and `MakeShadow`, and the CLI's
//! `texture make` ([`crate::tool`]).
//!
//! The source is decoded as stored (linear: RenderMan does no colour conversion), its MIP
//! pyramid built by 2 x 2 box reduction (level k is the k-times reduction, [`crate::mip`]) and
//! written as a tiled TIFF ([`crate::write`]). The request's filter and widths are checked
//! (a name the Specification gives, widths positive) and recorded in the error messages only:
//! the levels are always box-reduced, so that they are exactly the reduction the lookups
//! assume.
//!
//! A shadow map is made from a depth map: a 1-channel float TIFF with the world-to-screen and
//! world-to-camera matrices in Pixar's tags, as `Display "zfile"` writes it; it keeps one
//! level (depths are not averaged) and its matrices.

use std::path::Path;

use crate::load::{Image, decode};
use crate::mip::{MipLevel, Pyramid};
use crate::prepared::{MapKind, PreparedFile};
use crate::write::{Depth, Spec, write};
use crate::{ColorSpace, TextureError, Wrap};

/// Pixel filter names `MakeTexture` accepts (Spec 3.2's and the peers').
pub const FILTERS: [&str; 9] =
    ["box", "triangle", "gaussian", "catmull-rom", "sinc", "disk", "bessel", "mitchell", "lanczos"];

/// How to make a map.
#[derive(Debug, Clone, PartialEq)]
pub struct MakeOptions {
    /// Wrap modes in s and t.
    pub wrap: [Wrap; 2],
    /// The filter's name (checked against [`FILTERS`]).
    pub filter: String,
    /// Its widths in s and t.
    pub width: [f32; 2],
    /// Sample storage (None: float for float sources such as OpenEXR, else 8-bit).
    pub depth: Option<Depth>,
    /// Cube faces: their field of view in degrees.
    pub fov: f32,
}

impl Default for MakeOptions {
    fn default() -> Self {
        MakeOptions {
            wrap: [Wrap::Periodic; 2],
            filter: "box".into(),
            width: [1.0, 1.0],
            depth: None,
            fov: 90.0,
        }
    }
}

fn bad(file: &Path, message: String) -> TextureError {
    TextureError::Decode { file: file.to_path_buf(), message }
}

/// Checks `opts` for making `out`: a known filter name and positive widths.
///
/// # Errors
///
/// [`TextureError::Decode`] naming `out` and what is wrong.
pub fn check_options(opts: &MakeOptions, out: &Path) -> Result<(), TextureError> {
    if !FILTERS.contains(&opts.filter.as_str()) {
        return Err(bad(
            out,
            format!("unknown filter \"{}\" (one of {})", opts.filter, FILTERS.join(", ")),
        ));
    }
    if !opts.width.iter().all(|w| w.is_finite() && *w > 0.0) {
        return Err(bad(out, format!("filter widths {:?} must be positive", opts.width)));
    }
    Ok(())
}

/// The channels of `image` worth writing: 1 for grey, 3 for colour, 4 with alpha.
fn channels(image: &Image) -> u32 {
    let px = image.texels.chunks_exact(4);
    let alpha = px.clone().any(|p| p[3] != 1.0);
    let grey = px.clone().all(|p| p[0] == p[1] && p[1] == p[2]);
    match (grey, alpha) {
        (true, false) => 1,
        (true, true) => 2,
        (false, false) => 3,
        (false, true) => 4,
    }
}

/// The depth to write: the asked one, else float for a source with values outside [0, 1]
/// or an OpenEXR or float TIFF, else 8-bit.
fn depth_for(image: &Image, src: &Path, asked: Option<Depth>) -> Depth {
    asked.unwrap_or_else(|| {
        let ext = src.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        let outside = image.texels.iter().any(|v| !(0.0..=1.0).contains(v));
        let fine = image.texels.iter().any(|v| (v * 255.0 - (v * 255.0).round()).abs() > 1e-3);
        if outside || ext == "exr" || (fine && matches!(ext.as_str(), "tif" | "tiff")) {
            Depth::Float
        } else {
            Depth::Byte
        }
    })
}

fn make(
    src: &Path,
    out: &Path,
    kind: MapKind,
    wrap: [Wrap; 2],
    opts: &MakeOptions,
) -> Result<(), TextureError> {
    check_options(opts, out)?;
    let image = decode(src, ColorSpace::Linear)?;
    let spec = Spec {
        kind,
        wrap,
        depth: depth_for(&image, src, opts.depth),
        channels: channels(&image),
        matrices: None,
        fov_cot: None,
    };
    let pyramid = Pyramid::build(image);
    write_levels(out, &pyramid.levels, &spec)
}

fn write_levels(out: &Path, levels: &[MipLevel], spec: &Spec) -> Result<(), TextureError> {
    write(out, levels, spec).map_err(|source| TextureError::Io { file: out.to_path_buf(), source })
}

/// `MakeTexture`: a plain texture.
///
/// # Errors
///
/// The source cannot be read or decoded, the options are bad, or the output cannot be written.
pub fn make_texture(src: &Path, out: &Path, opts: &MakeOptions) -> Result<(), TextureError> {
    make(src, out, MapKind::Plain, opts.wrap, opts)
}

/// `MakeLatLongEnvironment`: longitude along s (periodic), latitude down t (clamped).
///
/// # Errors
///
/// As [`make_texture`].
pub fn make_latlong(src: &Path, out: &Path, opts: &MakeOptions) -> Result<(), TextureError> {
    make(src, out, MapKind::LatLong, [Wrap::Periodic, Wrap::Clamp], opts)
}

/// `MakeCubeFaceEnvironment`: the six square faces `px nx py ny pz nz` of one size, laid out
/// in three columns and two rows (`px py pz` above `nx ny nz`), seen with field of view
/// `opts.fov`.
///
/// # Errors
///
/// As [`make_texture`], or the faces are not squares of one size.
pub fn make_cube(faces: [&Path; 6], out: &Path, opts: &MakeOptions) -> Result<(), TextureError> {
    check_options(opts, out)?;
    if !(opts.fov.is_finite() && opts.fov > 0.0 && opts.fov < 180.0) {
        return Err(bad(out, format!("field of view {} is not between 0 and 180", opts.fov)));
    }
    let mut images = Vec::with_capacity(6);
    for f in faces {
        let im = decode(f, ColorSpace::Linear)?;
        if im.width != im.height {
            return Err(bad(
                f,
                format!("a cube face of {} x {} is not square", im.width, im.height),
            ));
        }
        if let Some(first) = images.first().map(|i: &Image| i.width)
            && first != im.width
        {
            return Err(bad(
                f,
                format!("a cube face of side {} among faces of side {first}", im.width),
            ));
        }
        images.push(im);
    }
    let n = images[0].width as usize;
    let (w, h) = (3 * n, 2 * n);
    let mut atlas = Image { width: w as u32, height: h as u32, texels: vec![0.0; 4 * w * h] };
    // px nx py ny pz nz -> columns 0 0 1 1 2 2, rows 0 1 0 1 0 1.
    for (k, im) in images.iter().enumerate() {
        let (col, row) = (k / 2, k % 2);
        for y in 0..n {
            let dst = 4 * ((row * n + y) * w + col * n);
            atlas.texels[dst..dst + 4 * n].copy_from_slice(&im.texels[4 * y * n..4 * (y + 1) * n]);
        }
    }
    let src = faces[0];
    let spec = Spec {
        kind: MapKind::CubeFace,
        wrap: [Wrap::Clamp; 2],
        depth: depth_for(&atlas, src, opts.depth),
        channels: channels(&atlas),
        matrices: None,
        fov_cot: Some(1.0 / (opts.fov.to_radians() / 2.0).tan()),
    };
    write_levels(out, &Pyramid::build(atlas).levels, &spec)
}

/// `MakeShadow`: a shadow map from a depth map (see the module).
///
/// # Errors
///
/// The depth map cannot be read, is not one channel of floats, or lacks its matrices; the
/// output cannot be written.
pub fn make_shadow(src: &Path, out: &Path) -> Result<(), TextureError> {
    let p = PreparedFile::open(src)?;
    let h = &p.header;
    let (Some(screen), Some(camera)) = (h.world_to_screen, h.world_to_camera) else {
        return Err(bad(src, "a depth map needs its world-to-screen and world-to-camera matrices (Pixar tags 33305, 33306)".into()));
    };
    if h.channels != 1 || !matches!(h.sample, crate::prepared::SampleType::Float(_)) {
        return Err(bad(src, "a depth map is one channel of float depths".into()));
    }
    let level =
        read_level(&p, 0).map_err(|source| TextureError::Io { file: src.to_path_buf(), source })?;
    let spec = Spec {
        kind: MapKind::Shadow,
        wrap: [Wrap::Clamp; 2],
        depth: Depth::Float,
        channels: 1,
        matrices: Some((screen, camera)),
        fov_cot: None,
    };
    write_levels(out, &[level], &spec)
}

/// Every texel of level `k` of a prepared file, RGBA.
///
/// # Errors
///
/// A chunk cannot be read or decoded.
pub fn read_level(p: &PreparedFile, k: usize) -> std::io::Result<MipLevel> {
    let d = p.header.levels[k];
    let (w, h) = (d.width as usize, d.height as usize);
    let mut texels = vec![0.0; 4 * w * h];
    let chunks = d.chunks_x * d.height.div_ceil(d.chunk_h);
    for c in 0..chunks {
        let chunk = p.read_chunk(k, c)?;
        let (x0, y0) =
            ((c % d.chunks_x * d.chunk_w) as usize, (c / d.chunks_x * d.chunk_h) as usize);
        let cw = d.chunk_w as usize;
        for y in 0..(d.chunk_h as usize).min(h - y0) {
            let n = cw.min(w - x0);
            let dst = 4 * ((y0 + y) * w + x0);
            texels[dst..dst + 4 * n].copy_from_slice(&chunk[4 * y * cw..4 * (y * cw + n)]);
        }
    }
    Ok(MipLevel { width: d.width, height: d.height, texels })
}

/// Writes a depth map: depths `z` (row by row, `width x height`) with the matrices, one
/// float channel, as `Display "zfile"` does.
///
/// # Errors
///
/// The file cannot be written.
pub fn write_depth(
    out: &Path,
    width: u32,
    height: u32,
    z: &[f32],
    world_to_screen: [f32; 16],
    world_to_camera: [f32; 16],
    kind: MapKind,
) -> std::io::Result<()> {
    let texels = z.iter().flat_map(|&v| [v, v, v, 1.0]).collect();
    let level = MipLevel { width, height, texels };
    let spec = Spec {
        kind,
        wrap: [Wrap::Clamp; 2],
        depth: Depth::Float,
        channels: 1,
        matrices: Some((world_to_screen, world_to_camera)),
        fov_cot: None,
    };
    write(out, &[level], &spec)
}

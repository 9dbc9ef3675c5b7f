//! The frame's output with everything a compositor reads (stage: film, the last step):
//! the beauty and its AOVs as a multi-part OpenEXR file, the header's camera and render
//! metadata, and the PNG preview's view transform (docs/outputs.md).
//!
//! Invariants: writes are atomic ([`crate::atomic`]); the file is a pure function of the
//! picture (the `exr` crate keeps custom attributes in a hash map, whose order changes from
//! run to run, so every header's attributes are put in name order after encoding, which
//! moves bytes only within the header); without AOVs it is a single-part file with the
//! top-level channels R, G, B, A, Z as before; with AOVs, part 0 is named `rgba` and holds
//! those channels, and each AOV is a part named after its layer with channels
//! `LAYER.CHANNEL`.

use std::io::{Seek, Write};
use std::path::Path;

use exr::prelude::*;
use reyes_scene::{Compression as Comp, Outputs, PixelType, PngView, Scene};

use crate::atomic::{WriteOptions, write_atomic};
use crate::early::EarlyBlocks;
use crate::output::{exr_error, format_of, io_error, png_bytes, read_all_parts};
use crate::{AovFilm, Film, FilmError};

/// One AOV layer of the picture: where its channels are in the [`AovFilm`].
#[derive(Debug, Clone, PartialEq)]
pub struct AovLayer {
    /// Layer (part) name.
    pub name: String,
    /// Channel names within the layer (`X`, `Y`, `Z`, ...).
    pub channels: Vec<&'static str>,
    /// First channel in the AOV film.
    pub start: usize,
    /// Written as 32-bit unsigned integers (ids).
    pub integer: bool,
    /// Pixel type of a float layer.
    pub pixel_type: PixelType,
    /// Compression.
    pub compression: Comp,
}

/// The header's metadata.
#[derive(Debug, Clone, PartialEq)]
pub struct Metadata {
    /// World to camera space (our camera space: +x right, +y up, +z forward), as Imath
    /// stores a matrix: row vectors, `p' = p M`, row-major.
    pub world_to_camera: [f32; 16],
    /// World to NDC (x right and y down over the screen window, in [0, 1]; the homogeneous
    /// divide gives them), as `world_to_camera`.
    pub world_to_ndc: [f32; 16],
    /// The screen window `[left, right, bottom, top]`.
    pub screen_window: [f32; 4],
    /// `software`: name and version.
    pub software: String,
    /// The scene file.
    pub scene: String,
    /// The seed.
    pub seed: u64,
    /// Samples per pixel `(nx, ny)`.
    pub samples: (u32, u32),
    /// The pixel filter, as `KIND WIDTHxHEIGHT`.
    pub filter: String,
    /// Render time in seconds (written only when the scene asks: `outputs.render_time`).
    pub render_time: Option<f32>,
}

impl Metadata {
    /// The metadata of `scene` read from `scene_path`, camera at shutter open.
    pub fn for_scene(scene: &Scene, scene_path: &str) -> Metadata {
        use glam::{Mat4, Vec3, Vec4};
        let cam = &scene.camera;
        let (w, h) = (scene.image.width as f32, scene.image.height as f32);
        let basis = reyes_scene::view::basis(
            Vec3::from(cam.eye),
            Vec3::from(cam.look_at),
            Vec3::from(cam.up),
        );
        let world_to_camera = basis.map_or(Mat4::IDENTITY, |b| b.world_to_camera(cam.eye.into()));
        let (c, k) = reyes_scene::view::raster_mapping(cam, w, h);
        // Camera to NDC (column vectors): ndc_x = (c.x + k.x x/z) / w, ndc_y = (c.y - k.y y/z)
        // / h under perspective (w' = z, z' = 1 so the matrix is invertible: z_ndc = 1/z);
        // without the divide under orthographic projection.
        let proj = match cam.projection {
            reyes_scene::Projection::Perspective => Mat4::from_cols(
                Vec4::new(k.x / w, 0.0, 0.0, 0.0),
                Vec4::new(0.0, -k.y / h, 0.0, 0.0),
                Vec4::new(c.x / w, c.y / h, 0.0, 1.0),
                Vec4::new(0.0, 0.0, 1.0, 0.0),
            ),
            reyes_scene::Projection::Orthographic => Mat4::from_cols(
                Vec4::new(k.x / w, 0.0, 0.0, 0.0),
                Vec4::new(0.0, -k.y / h, 0.0, 0.0),
                Vec4::new(0.0, 0.0, 1.0, 0.0),
                Vec4::new(c.x / w, c.y / h, 0.0, 1.0),
            ),
        };
        let a = w / h;
        let screen_window = cam.screen_window.unwrap_or(if a >= 1.0 {
            [-a, a, -1.0, 1.0]
        } else {
            [-1.0, 1.0, -1.0 / a, 1.0 / a]
        });
        let f = &scene.hider.filter;
        let fh = f.height.unwrap_or(f.width);
        Metadata {
            // Column-major of the column-vector matrix is row-major of its transpose.
            world_to_camera: world_to_camera.to_cols_array(),
            world_to_ndc: (proj * world_to_camera).to_cols_array(),
            screen_window,
            software: format!("reyes-render {}", env!("CARGO_PKG_VERSION")),
            scene: scene_path.to_string(),
            seed: scene.hider.seed,
            samples: scene.hider.pixel_samples,
            filter: format!("{:?} {}x{}", f.kind, f.width, fh),
            render_time: None,
        }
    }
}

/// Everything one output file holds.
#[derive(Debug, Clone, Copy)]
pub struct Picture<'a> {
    /// The beauty (and its Z).
    pub film: &'a Film,
    /// The AOVs and their layers (none: the beauty alone).
    pub aovs: Option<(&'a AovFilm, &'a [AovLayer])>,
    /// The scene's output settings.
    pub outputs: &'a Outputs,
    /// The header's metadata.
    pub metadata: &'a Metadata,
    /// Where the films' pixels lie in the whole frame, when they are a crop window's
    /// (None: they are the whole frame).
    pub placement: Option<Placement>,
    /// The beauty's blocks compressed while the frame rendered, if any: the write stores
    /// those it finds ready instead of compressing them again (whole frames only; the file
    /// is the same either way, see [`crate::early`]).
    pub early: Option<&'a EarlyBlocks>,
}

/// Where a crop window's pixels lie: the EXR's display window is the whole frame and its
/// data window the crop's pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    /// The whole frame's size in pixels.
    pub full: (u32, u32),
    /// The raster position of the films' top-left pixel in it.
    pub origin: (u32, u32),
}

/// Write `picture` to `path`, atomically: EXR (every layer, the metadata) or PNG (the
/// beauty through the view transform), by extension.
///
/// # Errors
///
/// As [`crate::write_with`].
pub fn write_picture(
    path: &Path,
    picture: &Picture,
    opts: &WriteOptions,
) -> std::result::Result<(), FilmError> {
    match format_of(path)? {
        crate::output::Format::Exr => {
            write_atomic(path, opts, &|w| encode_picture(path, picture, w))
        }
        crate::output::Format::Png => write_atomic(path, opts, &|w| {
            let bytes = png_bytes(picture.film, &picture.outputs.png);
            crate::output::encode_png_bytes(path, picture.film, &bytes, w)
        }),
    }
}

fn compression(c: Comp) -> Compression {
    match c {
        Comp::None => Compression::Uncompressed,
        Comp::Zip => Compression::ZIP16,
        Comp::Piz => Compression::PIZ,
        Comp::Dwaa => Compression::DWAA(None),
    }
}

pub(crate) fn encoding(c: Comp) -> Encoding {
    Encoding {
        compression: compression(c),
        blocks: Blocks::ScanLines,
        line_order: LineOrder::Increasing,
    }
}

fn samples(values: impl Iterator<Item = f32>, ty: PixelType) -> FlatSamples {
    match ty {
        PixelType::Float => FlatSamples::F32(values.collect()),
        PixelType::Half => FlatSamples::F16(values.map(f16::from_f32).collect()),
    }
}

/// The layer attributes every part carries: name, camera, screen window, software.
fn attributes(name: Option<&str>, m: &Metadata) -> LayerAttributes {
    let mut a = match name {
        Some(n) => LayerAttributes::named(n),
        None => LayerAttributes::default(),
    };
    let [l, r, b, t] = m.screen_window;
    a.screen_window_center = Vec2(0.5 * (l + r), 0.5 * (b + t));
    a.screen_window_width = r - l;
    a.world_to_camera = Some(m.world_to_camera);
    a.world_to_normalized_device = Some(m.world_to_ndc);
    a.software_name = Text::new_or_none(&m.software);
    a
}

fn encode_picture(
    path: &Path,
    p: &Picture,
    w: &mut (impl Write + Seek),
) -> std::result::Result<(), FilmError> {
    let film = p.film;
    let size = (film.width() as usize, film.height() as usize);
    let (full, origin) = match p.placement {
        Some(Placement { full: (fw, fh), origin: (x, y) }) => {
            ((fw as usize, fh as usize), Vec2(x as i32, y as i32))
        }
        None => (size, Vec2(0, 0)),
    };
    let placed = |mut a: LayerAttributes| {
        a.layer_position = origin;
        a
    };
    let o = p.outputs;
    let zbg = o.zbackground.value();
    let rgba = film.rgba();
    // Without pixels (`all == false`) when every block of the beauty is taken from `early`.
    let beauty = |all: bool| {
        let n = if all { rgba.len() } else { 0 };
        let plane = |k: usize| rgba[..n].iter().map(move |px| px[k]);
        let z = film.z()[..n].iter().map(|&z| if z == f32::INFINITY { zbg } else { z });
        let ty = o.pixel_type;
        vec![
            AnyChannel::new("R", samples(plane(0), ty)),
            AnyChannel::new("G", samples(plane(1), ty)),
            AnyChannel::new("B", samples(plane(2), ty)),
            AnyChannel::new("A", samples(plane(3), ty)),
            AnyChannel::new("Z", samples(z, PixelType::Float)),
        ]
    };
    let early = p.early.filter(|_| p.placement.is_none());
    let named = p.aovs.is_some();
    let mut top = attributes(named.then_some("rgba"), p.metadata);
    let m = p.metadata;
    let custom = &mut top.other;
    custom.insert(
        Text::from("reyesScene"),
        AttributeValue::Text(Text::new_or_panic(
            m.scene.chars().filter(char::is_ascii).collect::<String>(),
        )),
    );
    custom.insert(
        Text::from("reyesSeed"),
        AttributeValue::Text(Text::from(m.seed.to_string().as_str())),
    );
    custom.insert(
        Text::from("reyesPixelSamples"),
        AttributeValue::IntVec2(Vec2(m.samples.0 as i32, m.samples.1 as i32)),
    );
    custom.insert(Text::from("reyesFilter"), AttributeValue::Text(Text::from(m.filter.as_str())));
    custom.insert(Text::from("reyesZBackground"), AttributeValue::F32(zbg));
    if let Some(t) = m.render_time {
        custom.insert(Text::from("renderTime"), AttributeValue::F32(t));
    }
    let mut layers = vec![Layer::new(
        size,
        placed(top),
        encoding(o.compression),
        AnyChannels::sort(SmallVec::from_vec(beauty(early.is_none()))),
    )];
    if let Some((aov, list)) = p.aovs {
        for layer in list {
            let channels = layer
                .channels
                .iter()
                .enumerate()
                .map(|(k, c)| {
                    let values =
                        aov.data().iter().skip(layer.start + k).step_by(aov.channels()).copied();
                    let data = if layer.integer {
                        // Ids are exact non-negative integers in f32 (below 2^24).
                        FlatSamples::U32(values.map(|v| v as u32).collect())
                    } else {
                        samples(values, layer.pixel_type)
                    };
                    AnyChannel::new(format!("{}.{c}", layer.name).as_str(), data)
                })
                .collect();
            layers.push(Layer::new(
                size,
                placed(attributes(Some(&layer.name), p.metadata)),
                encoding(layer.compression),
                AnyChannels::sort(SmallVec::from_vec(channels)),
            ));
        }
    }
    let bounds = IntegerBounds::new((0, 0), full);
    let mut image = Image::from_layers(ImageAttributes::new(bounds), layers);
    let mut bytes = std::io::Cursor::new(Vec::new());
    let headers = image.write().infer_meta_data();
    let written = match early.filter(|e| headers.first().is_some_and(|h| e.fits(h))) {
        Some(e) => write_early(&image, headers, film, e, &mut bytes),
        None => {
            if early.is_some() {
                // Chunks made for another header: the beauty's pixels after all.
                let all = AnyChannels::sort(SmallVec::from_vec(beauty(true)));
                image.layer_data[0].channel_data = all;
            }
            image.write().to_buffered(&mut bytes)
        }
    };
    written.map_err(|e| exr_error(path, e))?;
    let mut bytes = bytes.into_inner();
    sort_header_attributes(&mut bytes).map_err(|reason| FilmError::BadExr {
        path: path.to_path_buf(),
        reason: format!("cannot order the header: {reason}"),
    })?;
    w.write_all(&bytes).map_err(|e| io_error(path, e))
}

/// Write `image` as its own writer would, with `headers` (its inferred ones), but with the
/// beauty's blocks (layer 0) from `early` (made from `film`), and every block still to be
/// compressed compressed in parallel in the current rayon pool. The blocks are stored in the
/// encoder's order (header by header, increasing y), so the bytes are the encoder's.
fn write_early(
    image: &Image<Layers<AnyChannels<FlatSamples>>>,
    headers: exr::meta::Headers,
    film: &Film,
    early: &EarlyBlocks,
    out: &mut std::io::Cursor<Vec<u8>>,
) -> exr::error::UnitResult {
    use exr::block::writer::ChunksWriter;
    use exr::image::write::layers::{LayersWriter, WritableLayers};
    use rayon::prelude::*;
    let layers = image.layer_data.create_writer(&headers);
    exr::block::write(out, headers, true, |meta, chunks| {
        let blocks: Vec<(usize, exr::block::BlockIndex)> =
            exr::block::enumerate_ordered_header_block_indices(&meta.headers).collect();
        let made: Vec<exr::error::Result<exr::block::chunk::Chunk>> = blocks
            .par_iter()
            .map(|&(i, index)| match index.layer {
                0 => early.chunk(film, i),
                _ => {
                    let data = layers.extract_uncompressed_block(&meta.headers, index);
                    exr::block::UncompressedBlock { index, data }.compress_to_chunk(&meta.headers)
                }
            })
            .collect();
        for (&(i, _), chunk) in blocks.iter().zip(made) {
            chunks.write_chunk(i, chunk?)?;
        }
        Ok(())
    })
}

/// Put every attribute of every header of the OpenEXR file `bytes` in name order, in place.
/// Headers keep their lengths, so the offset tables and chunks after them are unchanged.
fn sort_header_attributes(bytes: &mut [u8]) -> std::result::Result<(), String> {
    const MULTIPART: u32 = 0x1000;
    let flags =
        u32::from_le_bytes(bytes.get(4..8).ok_or("short file")?.try_into().map_err(|_| "short")?);
    let multipart = flags & MULTIPART != 0;
    let mut at = 8;
    loop {
        if multipart && bytes.get(at) == Some(&0) {
            return Ok(()); // the empty header ends the list
        }
        let start = at;
        let mut records: Vec<(Vec<u8>, Vec<u8>)> = Vec::new();
        while *bytes.get(at).ok_or("header runs off the end")? != 0 {
            let name_end = at + bytes[at..].iter().position(|&b| b == 0).ok_or("no name end")?;
            let type_end = name_end
                + 1
                + bytes[name_end + 1..].iter().position(|&b| b == 0).ok_or("no type end")?;
            let size_at = type_end + 1;
            let size = i32::from_le_bytes(
                bytes.get(size_at..size_at + 4).ok_or("no size")?.try_into().map_err(|_| "size")?,
            );
            let end = size_at + 4 + usize::try_from(size).map_err(|_| "negative size")?;
            if end > bytes.len() {
                return Err("attribute runs off the end".into());
            }
            records.push((bytes[at..name_end].to_vec(), bytes[at..end].to_vec()));
            at = end;
        }
        records.sort();
        let mut k = start;
        for (_, record) in &records {
            bytes[k..k + record.len()].copy_from_slice(record);
            k += record.len();
        }
        at += 1; // the header's terminating 0
        if !multipart {
            return Ok(());
        }
    }
}

/// The PNG view transform of one premultiplied linear pixel at `(x, y)`: exposure, optional
/// composite over the background, straight colour, sRGB encoding, then 8 bits with the 8x8
/// ordered dither (or rounding). Alpha stays linear (1 over a background).
pub fn view_pixel(p: [f32; 4], (x, y): (u32, u32), view: &PngView) -> [u8; 4] {
    let gain = 2.0_f32.powf(view.exposure);
    let a = p[3];
    let (rgb, alpha) = match view.background {
        Some(bg) => {
            let cover = a.clamp(0.0, 1.0);
            ([0, 1, 2].map(|k| gain * p[k] + (1.0 - cover) * bg[k]), 1.0)
        }
        None => ([0, 1, 2].map(|k| if a > 0.0 { gain * p[k] / a } else { 0.0 }), a),
    };
    let threshold = if view.dither { bayer8(x, y) } else { 0.5 };
    let q = |v: f32| -> u8 {
        if v.is_nan() {
            return 0;
        }
        (v.clamp(0.0, 1.0) * 255.0 + threshold).floor().min(255.0) as u8
    };
    [
        q(crate::srgb_encode(rgb[0])),
        q(crate::srgb_encode(rgb[1])),
        q(crate::srgb_encode(rgb[2])),
        q(alpha),
    ]
}

/// The 8x8 Bayer threshold at `(x, y)`, in (0, 1): `(M + 0.5) / 64`, `M` built from the 2x2
/// matrix `[[0, 2], [3, 1]]` with the lowest coordinate bits most significant.
pub fn bayer8(x: u32, y: u32) -> f32 {
    let m2 = |x: u32, y: u32| match (x & 1, y & 1) {
        (0, 0) => 0,
        (1, 0) => 2,
        (0, 1) => 3,
        _ => 1,
    };
    let m = 16 * m2(x, y) + 4 * m2(x >> 1, y >> 1) + m2(x >> 2, y >> 2);
    (m as f32 + 0.5) / 64.0
}

/// `v` as a channel stores it: rounded to half for a half channel.
pub fn as_stored(v: f32, half: bool) -> f32 {
    if half { f16::from_f32(v).to_f32() } else { v }
}

/// One channel of a file read back by [`read_layers`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReadChannel {
    /// The part's name (`None` for a single-part file without one).
    pub layer: Option<String>,
    /// The channel's full name (`N.X`, `R`).
    pub name: String,
    /// Samples as f32 (half and float channels; ids converted exactly).
    pub values: Vec<f32>,
    /// The samples as stored, for integer channels.
    pub integers: Option<Vec<u32>>,
    /// True for a 16-bit float channel.
    pub half: bool,
    /// The part's compression, as the `exr` crate names it.
    pub compression: String,
}

/// Read every channel of every part of an OpenEXR file (for tests and the golden harness).
///
/// # Errors
///
/// [`FilmError::Io`] or [`FilmError::Exr`] if the file cannot be read.
pub fn read_layers(path: &Path) -> std::result::Result<Vec<ReadChannel>, FilmError> {
    let image = read_all_parts(path)?;
    let mut out = Vec::new();
    for layer in &image.layer_data {
        let name = layer.attributes.layer_name.as_ref().map(|n| n.to_string());
        for c in &layer.channel_data.list {
            let integers = match &c.sample_data {
                FlatSamples::U32(v) => Some(v.clone()),
                _ => None,
            };
            out.push(ReadChannel {
                layer: name.clone(),
                name: c.name.to_string(),
                values: c.sample_data.values_as_f32().collect(),
                integers,
                half: matches!(c.sample_data, FlatSamples::F16(_)),
                compression: format!("{:?}", layer.encoding.compression),
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bayer_thresholds_are_the_64_levels_once_each() {
        let mut seen: Vec<u32> =
            (0..64).map(|k| (bayer8(k % 8, k / 8) * 64.0 - 0.5) as u32).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..64).collect::<Vec<_>>());
        // The 2x2 corner is the classic [[0, 2], [3, 1]] pattern at the top level (times 16).
        assert_eq!(
            [bayer8(0, 0), bayer8(1, 0), bayer8(0, 1), bayer8(1, 1)].map(|t| (t * 64.0) as u32),
            [0, 32, 48, 16]
        );
    }

    #[test]
    fn dither_preserves_the_mean_of_a_flat_area() {
        // Over an 8x8 tile the thresholds are (k + 0.5) / 64, k = 0..63, so the mean of
        // floor(255 v + t) is 255 v to within half of 1/64 (the level spacing).
        let view = PngView { exposure: 0.0, background: None, dither: true };
        for code in [0.2_f32, 17.3, 100.5, 128.9, 254.2] {
            let encoded = code / 255.0;
            let linear = crate::srgb_decode(encoded);
            let mut sum = 0.0;
            for y in 0..8 {
                for x in 0..8 {
                    let q = view_pixel([linear, linear, linear, 1.0], (x, y), &view);
                    assert!((f32::from(q[0]) - 255.0 * crate::srgb_encode(linear)).abs() < 1.0);
                    sum += f32::from(q[0]);
                }
            }
            let exact = 255.0 * crate::srgb_encode(linear);
            assert!(
                (sum / 64.0 - exact).abs() <= 0.5 / 64.0 + 1e-3,
                "{code}: {} vs {exact}",
                sum / 64.0
            );
        }
    }

    #[test]
    fn exposure_and_background_are_applied_in_linear_light() {
        let plain = PngView { exposure: 0.0, background: None, dither: false };
        // One stop doubles linear light: 0.25 -> 0.5.
        let up = PngView { exposure: 1.0, ..plain };
        assert_eq!(
            view_pixel([0.25, 0.25, 0.25, 1.0], (0, 0), &up),
            view_pixel([0.5, 0.5, 0.5, 1.0], (0, 0), &plain)
        );
        // Half coverage of premultiplied 0.2 over a background of 0.6: 0.2 + 0.5 * 0.6 = 0.5,
        // opaque.
        let over = PngView { background: Some([0.6, 0.6, 0.6]), ..plain };
        assert_eq!(
            view_pixel([0.2, 0.2, 0.2, 0.5], (3, 5), &over),
            view_pixel([0.5, 0.5, 0.5, 1.0], (0, 0), &plain)
        );
        // Without dither, the nearest code, as the plain writer.
        assert_eq!(
            view_pixel([0.5, 0.25, 0.0, 0.5], (0, 0), &plain),
            crate::output::png_pixel([0.5, 0.25, 0.0, 0.5])
        );
    }

    #[test]
    fn header_attributes_are_put_in_name_order() {
        // A hand-made single-part header: magic, version, then "b" before "a", then 0.
        let mut bytes = vec![0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
        let attr = |name: &str, v: u8| {
            let mut a = name.as_bytes().to_vec();
            a.extend_from_slice(b"\0int\0");
            a.extend_from_slice(&4i32.to_le_bytes());
            a.extend_from_slice(&[v, 0, 0, 0]);
            a
        };
        bytes.extend(attr("b", 2));
        bytes.extend(attr("a", 1));
        bytes.push(0);
        bytes.extend_from_slice(b"rest");
        let mut expect = bytes[..8].to_vec();
        expect.extend(attr("a", 1));
        expect.extend(attr("b", 2));
        expect.push(0);
        expect.extend_from_slice(b"rest");
        assert_eq!(sort_header_attributes(&mut bytes), Ok(()));
        assert_eq!(bytes, expect);
        // Truncated: an error, not a panic.
        let mut short = expect[..12].to_vec();
        assert!(sort_header_attributes(&mut short).is_err());
    }
}
